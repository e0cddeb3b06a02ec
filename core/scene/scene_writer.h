// A scene written back to Nori-style XML: a parsed description with render settings written over it
// (the camera with its pixel filter, the sampler, the integrator), as the viewer's "Save as" and Stats
// panel and the Python module's Scene.to_xml write it. Everything else of the description (shapes,
// emitters, BSDFs, and every property the settings do not cover) is written as parsed, so the file
// reads back to the same description and the same settings.
#pragma once

#include <optional>
#include <string>

#include "core/math/vec.h"
#include "core/render/render_settings.h"
#include "core/scene/scene_desc.h"

namespace penumbra {

// A camera given by where it is, what it looks at and which way is up (a <lookat>).
struct CameraLookAt {
  Vec3 origin{0.f};
  Vec3 target{0.f, 0.f, 1.f};
  Vec3 up{0.f, 1.f, 0.f};
};

struct SceneWriteOptions {
  // Non-empty: the directory the XML will be read from. Every relative string property that names an
  // existing file from its node's directory (OBJ meshes) is rewritten to name it from there: relative
  // when the two share a root, absolute otherwise.
  std::string outputDir;
  // The camera as a lookat (the viewer's orbit), written as <lookat> when it builds the settings'
  // camera toWorld to float rounding. Otherwise, and without it, the toWorld is written as the
  // description's own <lookat> while the camera is still exactly the description's, else as a
  // <matrix>.
  std::optional<CameraLookAt> cameraLookAt;
};

// The description with `settings` written into it:
//   camera     toWorld (see SceneWriteOptions::cameraLookAt), fov, width, height; nearClip and farClip
//              and the <rfilter> only where they differ from what the description gives;
//   sampler    its canonical type name, sampleCount and seed (its other properties stay);
//   integrator the strategy's XML type and canonical properties (strategy axes): the saved file
//              names the light selection and counts it renders with. Of the description's own
//              properties only those stay that neither its strategy nor the written one reads.
// A missing camera, sampler or integrator is added. Nothing is validated beyond what the description
// already passed; the result is what writeSceneXml serialises.
SceneNode sceneWithSettings(const SceneNode& desc, const RenderSettings& settings,
                            const SceneWriteOptions& options = {});

// writeSceneXml(sceneWithSettings(desc, settings, options)).
std::string writeScene(const SceneNode& desc, const RenderSettings& settings,
                       const SceneWriteOptions& options = {});

// The file-path rewriting of SceneWriteOptions::outputDir on its own: every node of the tree then has
// `dir` (made absolute) as its baseDir, so the tree still resolves to the same files.
void rebaseFilePaths(SceneNode& root, const std::string& dir);

}  // namespace penumbra
