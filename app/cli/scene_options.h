// Options shared by the subcommands that load a scene: the scene path and --set overrides.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/scene/scene_builder.h"

namespace penumbra::cli {

struct SceneOptions {
  std::string scenePath;
  std::vector<std::string> sets;  // "tag.property=value"

  void addTo(CLI::App& cmd, bool sceneRequired = true);
  // Splits --set values at '='; throws penumbra::Error on a malformed one.
  std::vector<std::pair<std::string, std::string>> overrides() const;
  // Loads the scene (or the built-in default when scenePath is empty), printing warnings to stderr.
  LoadedScene load() const;
};

}  // namespace penumbra::cli
