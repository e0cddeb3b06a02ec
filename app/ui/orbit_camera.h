// The viewer's orbit camera: orbit, pan and dolly of a scene camera about a target, with their
// limits (never under the scene's horizon plane, never through a surface). No GL, no engine: each
// gesture returns the camera's new toWorld and the ViewerController applies it as a settings change.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include <glm/mat4x4.hpp>

#include "core/math/vec.h"
#include "core/render/camera.h"
#include "core/scene/scene_desc.h"
#include "core/scene/scene_writer.h"
#include "core/world/scene.h"

namespace penumbra::ui {

// Orbit camera state derived from a Nori toWorld (columns: left, up, forward, origin).
struct OrbitCamera {
  Vec3 target{0.f};
  Vec3 worldUp{0, 1, 0};  // the scene's <lookat> up when it has one, else the camera's up
  float distance = 1.f;
  // Lowest elevation (sine of the angle above the plane through the target normal to worldUp) the
  // orbit may reach: the upper hemisphere, or the scene camera's own elevation when that is lower.
  float minElevationSin = 0.f;
  // The scene's horizon plane, fixed while the target pans: through the scene's target, normal to
  // worldUp. Orbit and pan keep the camera at least `minHeight` above it (0, or the scene camera's
  // own height when that is lower), so no move takes it under the floor.
  Vec3 horizonPoint{0.f};
  float minHeight = 0.f;
  bool moved = false;  // the user orbited, panned or dollied since the scene's camera was set
  // The camera is the lookat (origin, target, worldUp): the scene's <lookat>, or an orbit, pan or
  // dolly from one. Save as then writes a <lookat>, so the orbit survives a reload.
  bool isLookAt = false;
};

// What cameraLimitNote() says when a move stopped at the horizon plane, or in front of a surface.
inline constexpr const char* kCameraLimitNotes[2] = {
    "stopped at the scene's horizon: the camera stays above the floor plane",
    "stopped in front of a surface: the camera stays outside the objects"};

// Nori lookAt: columns (left, up, forward, origin).
glm::mat4 lookAt(const Vec3& origin, const Vec3& target, const Vec3& up);

// The gestures on one scene's camera. Orbit, pan and dolly keep the orbit's limits: never under the
// scene's horizon plane (see OrbitCamera), and pan and dolly stop in front of the first surface on the
// way (a camera inside an object sees black); limitNote() says when a move was stopped.
class OrbitControl {
 public:
  // The orbit about `camera` in `scene`: about the target of the scene's <lookat> (from `desc`)
  // while the camera is still the file's (`fileCamera`), else about the point in front of it at the
  // distance of the scene's centre. Clears the limit note.
  void reset(const CameraDesc& camera, const CameraDesc& fileCamera, const SceneNode& desc,
             std::shared_ptr<const Scene> scene);
  // Takes an earlier orbit back (a reload that keeps the user's camera).
  void restore(const OrbitCamera& state) { orbit_ = state; }

  // Each gesture returns the camera's new toWorld, or nothing when the camera stays where it is.
  std::optional<glm::mat4> orbit(const CameraDesc& camera, float dxPixels, float dyPixels);
  std::optional<glm::mat4> pan(const CameraDesc& camera, float dxPixels, float dyPixels);
  std::optional<glm::mat4> dolly(const CameraDesc& camera, float wheelSteps);

  const OrbitCamera& state() const { return orbit_; }
  const std::string& limitNote() const { return limitNote_; }
  // The camera as the lookat the scene writer writes, while it is one.
  std::optional<CameraLookAt> lookAt(const CameraDesc& camera) const;

 private:
  std::optional<glm::mat4> moveCamera(const CameraDesc& camera, const Vec3& origin, const Vec3& target);
  float clearDistance(const CameraDesc& camera, const Vec3& from, const Vec3& direction, float wanted) const;

  OrbitCamera orbit_;
  std::string limitNote_;
  std::shared_ptr<const Scene> scene_;
};

}  // namespace penumbra::ui
