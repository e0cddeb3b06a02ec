// SceneNode tree → a renderable Scene plus the RenderSettings it asks for. This is where type names
// are resolved ("sphere", "obj", "ao", ...), aliases of the assignment's scenes are accepted, ranges are
// validated with the offending line, and unread properties become warnings.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/render/render_settings.h"
#include "core/scene/scene_desc.h"
#include "core/world/scene.h"

namespace penumbra {

// Ranges the builder accepts (the viewer's fields clamp to the same ones).
inline constexpr int64_t kMaxSampleCount = 1 << 24;     // <sampler sampleCount>
inline constexpr int64_t kMaxShadingSamples = 1 << 16;  // the integrator's sample counts

struct LoadedScene {
  SceneNode desc;  // the parsed description, overrides applied (the viewer edits and saves it)
  std::shared_ptr<const Scene> scene;
  RenderSettings settings;
  std::vector<std::string> warnings;
  std::string path;  // the file it came from ("" for built-in scenes)
};

// Parses, applies "tag.property=value" overrides (--set), builds. Throws penumbra::Error.
LoadedScene loadScene(const std::string& path,
                      const std::vector<std::pair<std::string, std::string>>& overrides = {});
LoadedScene loadSceneFromString(const std::string& xml, const std::string& nameForErrors,
                                const std::string& baseDir,
                                const std::vector<std::pair<std::string, std::string>>& overrides = {});
// Builds geometry, lights and settings from a parsed description.
LoadedScene buildScene(SceneNode desc);
// Only the settings (camera, filter, sampler, integrator): cheap, no geometry. Used when the viewer
// edits settings of an already built scene. `areaLights` is the built scene's count of area lights,
// which decides the default light selection; without it the description's sphere lights are counted
// (a mesh's lights are known only once it is loaded).
RenderSettings buildSettings(const SceneNode& desc, std::vector<std::string>* warnings = nullptr,
                             std::optional<size_t> areaLights = std::nullopt);

// The scene `penumbra` opens with no arguments: a copy of scenes/hw2/Tests/sphere-solid.xml, a
// sphere on a plane lit by a sphere light.
const char* defaultSceneXml();

}  // namespace penumbra
