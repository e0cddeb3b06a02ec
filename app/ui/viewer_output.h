// What the viewer writes: the displayed accumulation as an image, and the live scene as XML (the scene
// writer, core/scene/scene_writer.h). Both atomic; both return a status message and throw
// penumbra::Error on failure.
#pragma once

#include <optional>
#include <string>

#include "core/render/engine.h"
#include "core/scene/scene_writer.h"

namespace penumbra::ui {

// PNG of the display (`exposure` applied, sRGB), EXR/PFM of the accumulation, with the settings, spp,
// time and scene (`scenePath`, "" for the built-in scene) as metadata. A light-share snapshot is
// saved as the split (EXR/PFM) or its false-colour map (PNG).
std::string saveSnapshotImage(const std::string& path, const FilmSnapshot& snapshot, bool lightShare,
                              const RenderSettings& settings, const std::string& scenePath, float exposure);

// The description with `settings` written into it, to `path`; mesh paths are rewritten to load from
// the file's directory.
std::string saveSceneFile(const std::string& path, const SceneNode& desc, const RenderSettings& settings,
                          const std::optional<CameraLookAt>& cameraLookAt);

}  // namespace penumbra::ui
