// The scenes the analysis unit tests render: the analytic scene (closed-form reference) and the
// assignment's sphere scene, loaded small.
#pragma once

#include <string>

#include "core/scene/scene_builder.h"

namespace penumbra::test {

inline std::string analyticScene() {
  return PENUMBRA_SOURCE_DIR "/scenes/analytic/plane-sphere-light.xml";
}
inline std::string sphereScene() {
  return PENUMBRA_SOURCE_DIR "/scenes/hw2/Tests/sphere-area.xml";
}

// The scene at size × size pixels.
inline LoadedScene loadSmall(const std::string& path, int size) {
  return loadScene(path, {{"camera.width", std::to_string(size)}, {"camera.height", std::to_string(size)}});
}

}  // namespace penumbra::test
