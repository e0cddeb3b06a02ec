#include "app/ui/reload_rules.h"

namespace penumbra::ui {

ReloadedSettings keepUserChanges(const RenderSettings& oldFile, const RenderSettings& live,
                                 const RenderSettings& newFile) {
  ReloadedSettings out{newFile, {}};
  RenderSettings& s = out.settings;
  auto keep = [&](bool userChanged, bool fileSame, const char* name, auto apply) {
    if (userChanged && fileSame) {
      apply();
      out.kept.push_back(name);
    }
  };
  keep(!(live.camera == oldFile.camera), newFile.camera == oldFile.camera, "camera",
       [&] { s.camera = live.camera; });
  keep(!(live.integrator == oldFile.integrator), newFile.integrator == oldFile.integrator, "integrator",
       [&] { s.integrator = live.integrator; });
  keep(live.samplerKind != oldFile.samplerKind || live.sampleCount != oldFile.sampleCount ||
           live.seed != oldFile.seed,
       newFile.samplerKind == oldFile.samplerKind && newFile.sampleCount == oldFile.sampleCount &&
           newFile.seed == oldFile.seed,
       "sampler",
       [&] { s.samplerKind = live.samplerKind, s.sampleCount = live.sampleCount, s.seed = live.seed; });
  return out;
}

std::string reloadStatus(const std::string& fileName, const std::vector<std::string>& kept) {
  std::string status = "reloaded " + fileName;
  if (!kept.empty()) {
    status += "; kept your ";
    for (size_t i = 0; i < kept.size(); ++i) status += (i ? ", " : "") + kept[i];
  }
  return status;
}

}  // namespace penumbra::ui
