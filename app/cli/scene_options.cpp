#include "app/cli/scene_options.h"

#include <cstdio>

#include "core/math/error.h"

namespace penumbra::cli {

void SceneOptions::addTo(CLI::App& cmd, bool sceneRequired) {
  auto* opt = cmd.add_option("scene", scenePath, "Scene file (Nori-style XML)");
  if (sceneRequired) opt->required();
  cmd.add_option("--set", sets,
                 "Override a scene property, e.g. --set integrator.measure=area --set sampler.sampleCount=64")
      ->type_name("TAG.PROPERTY=VALUE");
}

std::vector<std::pair<std::string, std::string>> SceneOptions::overrides() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& s : sets) {
    size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw Error("--set " + s + ": expected TAG.PROPERTY=VALUE, e.g. integrator.measure=area");
    out.emplace_back(s.substr(0, eq), s.substr(eq + 1));
  }
  return out;
}

LoadedScene SceneOptions::load() const {
  LoadedScene loaded = scenePath.empty()
                           ? loadSceneFromString(defaultSceneXml(), "<built-in scene>", ".", overrides())
                           : loadScene(scenePath, overrides());
  for (const std::string& w : loaded.warnings) std::fprintf(stderr, "%s\n", w.c_str());
  return loaded;
}

}  // namespace penumbra::cli
