// Perspective pinhole camera with Nori's conventions: looks down +z in camera space, x = left,
// y = up; `fov` is the horizontal field of view in degrees; image coordinates start top-left.
#pragma once

#include <glm/mat4x4.hpp>

#include "core/geometry/ray.h"
#include "core/math/vec.h"

namespace penumbra {

struct CameraDesc {
  glm::mat4 toWorld{1.f};
  float fovDegrees = 30.f;
  int width = 1280;
  int height = 720;
  float nearClip = 1e-4f;
  float farClip = 1e4f;
};

class PerspectiveCamera {
 public:
  PerspectiveCamera() = default;
  explicit PerspectiveCamera(const CameraDesc& desc);

  // Ray through image position `pixelPos` (continuous, in pixels: (0,0) top-left corner).
  Ray generateRay(Vec2 pixelPos) const {
    float sx = pixelPos.x * invWidth_, sy = pixelPos.y * invHeight_;
    Vec3 dCam((1.f - 2.f * sx) * tanHalfX_, (1.f - 2.f * sy) * tanHalfY_, 1.f);
    float invLen = 1.f / glm::length(dCam);
    dCam *= invLen;  // dCam.z = invLen
    Ray ray;
    ray.o = origin_;
    ray.d = glm::normalize(right_ * dCam.x + up_ * dCam.y + forward_ * dCam.z);
    ray.tMin = desc_.nearClip / dCam.z;
    ray.tMax = desc_.farClip / dCam.z;
    return ray;
  }

  // Inverse of generateRay's direction mapping: the image position a world direction projects to.
  // Returns false when the direction points behind the camera.
  bool project(const Vec3& worldDir, Vec2& pixelPos) const;

  const CameraDesc& desc() const { return desc_; }
  int width() const { return desc_.width; }
  int height() const { return desc_.height; }
  const Vec3& origin() const { return origin_; }
  const Vec3& forward() const { return forward_; }

 private:
  CameraDesc desc_;
  Vec3 origin_{0.f}, right_{1, 0, 0}, up_{0, 1, 0}, forward_{0, 0, 1};  // right_ is camera +x (left)
  float tanHalfX_ = 0.f, tanHalfY_ = 0.f, invWidth_ = 0.f, invHeight_ = 0.f;
};

}  // namespace penumbra
