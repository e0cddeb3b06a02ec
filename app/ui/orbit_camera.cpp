#include "app/ui/orbit_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/geometry/ray.h"
#include "core/geometry/surface_hit.h"
#include "core/math/frame.h"

namespace penumbra::ui {

glm::mat4 lookAt(const Vec3& origin, const Vec3& target, const Vec3& up) {
  Vec3 dir = glm::normalize(target - origin);
  Vec3 left = glm::cross(up, dir);
  if (glm::length(left) < 1e-6f)
    left = glm::cross(std::abs(dir.z) < 0.9f ? Vec3(0, 0, 1) : Vec3(1, 0, 0), dir);
  left = glm::normalize(left);
  Vec3 newUp = glm::normalize(glm::cross(dir, left));
  return cameraToWorld(origin, left, newUp, dir);
}

namespace {

// Equal up to float rounding of the same construction (a lookat rebuilt from its parts).
bool matricesClose(const glm::mat4& a, const glm::mat4& b) {
  float scale = 1.f;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) scale = std::max(scale, std::abs(b[c][r]));
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!(std::abs(a[c][r] - b[c][r]) <= 1e-5f * scale)) return false;
  return true;
}

// The scene camera's toWorld property, when it was written with <lookat>.
const Property* cameraLookAt(const SceneNode& desc) {
  const SceneNode* cam = desc.child("camera");
  if (!cam) return nullptr;
  for (const Property& p : cam->props.properties())
    if (p.name == "toWorld" && p.type == PropertyType::Transform && p.hasLookAt && !p.fromOverride) return &p;
  return nullptr;
}

float heightAbove(const OrbitCamera& o, const Vec3& p) {
  return glm::dot(p - o.horizonPoint, o.worldUp);
}

constexpr const char* kBelowHorizon = kCameraLimitNotes[0];
constexpr const char* kAtSurface = kCameraLimitNotes[1];

}  // namespace

void OrbitControl::reset(const CameraDesc& camera, const CameraDesc& fileCamera, const SceneNode& desc,
                         std::shared_ptr<const Scene> scene) {
  scene_ = std::move(scene);
  const glm::mat4& m = camera.toWorld;
  Vec3 origin(m[3]), forward = glm::normalize(Vec3(m[2]));
  orbit_.worldUp = glm::normalize(Vec3(m[1]));
  orbit_.moved = false;
  orbit_.isLookAt = false;
  limitNote_.clear();
  // The horizon plane through the target: the camera stays above it, or at its own height if lower.
  auto setHorizon = [&] {
    orbit_.horizonPoint = orbit_.target;
    orbit_.minHeight = std::min(0.f, glm::dot(origin - orbit_.target, orbit_.worldUp));
  };
  // The scene names its target: orbit about exactly that point (the camera is the file's).
  const Property* look = cameraLookAt(desc);
  if (look && camera.toWorld == fileCamera.toWorld && glm::length(look->lookAtTarget - origin) > 1e-6f &&
      glm::length(look->lookAtUp) > 1e-6f) {
    orbit_.target = look->lookAtTarget;
    orbit_.distance = glm::length(look->lookAtTarget - origin);
    Vec3 up = glm::normalize(look->lookAtUp);
    if (std::abs(glm::dot(up, forward)) < 0.999f) orbit_.worldUp = up;
    orbit_.minElevationSin = std::min(0.f, glm::dot(glm::normalize(origin - orbit_.target), orbit_.worldUp));
    // The camera is exactly the lookat about that target (no transform after the <lookat>).
    orbit_.isLookAt = matricesClose(ui::lookAt(origin, orbit_.target, orbit_.worldUp), m);
    setHorizon();
    return;
  }
  float distance = 0.f;
  if (scene_) {
    Bounds b = scene_->geometry.bounds();
    if (!b.empty()) distance = glm::dot(b.center() - origin, forward);
    // A huge ground plane moves the centre far away: prefer the distance to the nearest object
    // centre-ish point when the bound is unreasonable.
    if (!(distance > 1e-3f) || distance > 10.f * glm::length(origin - b.center()) + 1.f)
      distance = glm::length(b.center() - origin);
  }
  if (!(distance > 1e-3f) || !std::isfinite(distance)) distance = 1.f;
  orbit_.distance = distance;
  orbit_.target = origin + forward * distance;
  orbit_.minElevationSin = std::min(0.f, glm::dot(-forward, orbit_.worldUp));
  setHorizon();
}

std::optional<CameraLookAt> OrbitControl::lookAt(const CameraDesc& camera) const {
  if (!orbit_.isLookAt) return std::nullopt;
  return CameraLookAt{Vec3(camera.toWorld[3]), orbit_.target, orbit_.worldUp};
}

// The camera at `origin`, looking about `target` as before: a lookat camera is rebuilt from the two,
// any other keeps its rotation.
std::optional<glm::mat4> OrbitControl::moveCamera(const CameraDesc& camera, const Vec3& origin,
                                                  const Vec3& target) {
  glm::mat4 toWorld = camera.toWorld;
  if (orbit_.isLookAt) {
    toWorld = ui::lookAt(origin, target, orbit_.worldUp);
    // Far from the world's origin a camera dollied close to its target rounds onto it (floats are
    // ~0.1 apart at 1e6): with no direction to look along, the camera stays where it is.
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(toWorld[c][r])) return std::nullopt;
  } else {
    toWorld[3] = glm::vec4(origin, 1.f);
  }
  orbit_.moved = true;
  orbit_.target = target;
  return toWorld;
}

float OrbitControl::clearDistance(const CameraDesc& camera, const Vec3& from, const Vec3& direction,
                                  float wanted) const {
  if (!scene_ || !(wanted > 0.f)) return wanted;
  const float nearGap = 2.f * camera.nearClip;
  Ray ray{from, direction, 0.f, wanted * 1.05f + nearGap};
  SurfaceHit hit;
  if (!scene_->geometry.intersect(ray, hit)) return wanted;
  // Stop short of the surface by 2 % of the way to it (at least twice the near clip distance).
  const float gap = std::max(nearGap, 0.02f * hit.t);
  return std::clamp(hit.t - gap, 0.f, wanted);
}

std::optional<glm::mat4> OrbitControl::orbit(const CameraDesc& camera, float dx, float dy) {
  const glm::mat4& m = camera.toWorld;
  Vec3 origin(m[3]);
  Vec3 offset = origin - orbit_.target;
  const float k = 0.005f;  // radians per pixel
  glm::mat4 yaw = glm::rotate(glm::mat4(1.f), dx * k, orbit_.worldUp);
  offset = Vec3(yaw * glm::vec4(offset, 0.f));
  Vec3 left = glm::normalize(glm::cross(orbit_.worldUp, -offset));
  Vec3 pitched = Vec3(glm::rotate(glm::mat4(1.f), -dy * k, left) * glm::vec4(offset, 0.f));
  // Stop short of the poles, where the up vector would flip, and of the lower hemisphere (below the
  // ground the image goes black): the pitch stops at the limit rather than past it. A target panned
  // below the horizon plane cannot take the camera under it either.
  const float elevation = glm::dot(glm::normalize(pitched), orbit_.worldUp);
  const bool aboveFloor = heightAbove(orbit_, orbit_.target + pitched) >= orbit_.minHeight - 1e-6f ||
                          heightAbove(orbit_, orbit_.target + pitched) >= heightAbove(orbit_, origin);
  if (std::abs(elevation) < 0.995f && elevation >= orbit_.minElevationSin - 1e-6f && aboveFloor) {
    offset = pitched;
    limitNote_.clear();
  } else if (dy != 0.f && (elevation < orbit_.minElevationSin - 1e-6f || !aboveFloor)) {
    limitNote_ = kBelowHorizon;
  }
  orbit_.isLookAt = true;  // an orbit makes the camera the lookat about the target
  return moveCamera(camera, orbit_.target + offset, orbit_.target);
}

std::optional<glm::mat4> OrbitControl::pan(const CameraDesc& camera, float dx, float dy) {
  const glm::mat4& m = camera.toWorld;
  Vec3 left(m[0]), up(m[1]), origin(m[3]);
  // One pixel moves the target by the size of a pixel at the target's distance.
  float pixel = 2.f * orbit_.distance * std::tan(glm::radians(camera.fovDegrees) * 0.5f) /
                float(std::max(camera.width, 1));
  Vec3 shift = (left * dx + up * dy) * pixel;
  limitNote_.clear();
  // Never below the horizon plane: the part of the shift that would go there is dropped.
  const float below = orbit_.minHeight - heightAbove(orbit_, origin + shift);
  if (below > 0.f && glm::dot(shift, orbit_.worldUp) < 0.f) {
    shift += std::min(below, -glm::dot(shift, orbit_.worldUp)) * orbit_.worldUp;
    limitNote_ = kBelowHorizon;
  }
  const float length = glm::length(shift);
  if (!(length > 0.f)) return std::nullopt;
  const float clear = clearDistance(camera, origin, shift / length, length);
  if (clear < length) {
    shift *= clear / length;
    limitNote_ = kAtSurface;
  }
  return moveCamera(camera, origin + shift, orbit_.target + shift);
}

std::optional<glm::mat4> OrbitControl::dolly(const CameraDesc& camera, float steps) {
  const glm::mat4& m = camera.toWorld;
  const Vec3 forward = glm::normalize(Vec3(m[2])), origin(m[3]);
  const float wanted = std::clamp(orbit_.distance * std::pow(0.9f, steps), 1e-3f, 1e5f);
  float distance = wanted;
  limitNote_.clear();
  // Moving back while looking up lowers the camera: not under the horizon plane.
  const float rise = -glm::dot(forward, orbit_.worldUp);  // height gained per unit of distance
  if (rise < 0.f && distance > orbit_.distance) {
    const float lowest = heightAbove(orbit_, orbit_.target);
    const float maxDistance = (orbit_.minHeight - lowest) / rise;
    if (distance > maxDistance) {
      distance = std::max(orbit_.distance, maxDistance);
      limitNote_ = kBelowHorizon;
    }
  }
  // Not through a surface, forwards or backwards.
  const float move = orbit_.distance - distance;
  const float clear = clearDistance(camera, origin, move > 0.f ? forward : -forward, std::abs(move));
  if (clear < std::abs(move)) {
    distance = orbit_.distance - std::copysign(clear, move);
    limitNote_ = kAtSurface;
  }
  orbit_.distance = distance;
  return moveCamera(camera, orbit_.target - forward * distance, orbit_.target);
}

}  // namespace penumbra::ui
