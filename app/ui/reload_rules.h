// What a reload of the open scene file keeps of the user's changes: a setting the user changed in the
// UI (camera, integrator, sampler) survives unless the file changed that same setting.
#pragma once

#include <string>
#include <vector>

#include "core/render/render_settings.h"

namespace penumbra::ui {

struct ReloadedSettings {
  RenderSettings settings;        // the new file's, with the user's surviving changes
  std::vector<std::string> kept;  // which: "camera", "integrator", "sampler", in that order
};

// `oldFile`: the settings the file gave before, `live`: the viewer's, `newFile`: the file's now.
ReloadedSettings keepUserChanges(const RenderSettings& oldFile, const RenderSettings& live,
                                 const RenderSettings& newFile);

// "reloaded sphere.xml; kept your camera, limits" (just "reloaded sphere.xml" when nothing was kept).
std::string reloadStatus(const std::string& fileName, const std::vector<std::string>& kept);

}  // namespace penumbra::ui
