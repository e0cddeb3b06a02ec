// Perspective pinhole camera with Nori's conventions: looks down +z in camera space, x = left,
// y = up; `fov` is the horizontal field of view in degrees; image coordinates start top-left.
#pragma once

#include <glm/mat4x4.hpp>

#include <cmath>

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

  bool operator==(const CameraDesc&) const = default;
};

class PerspectiveCamera {
 public:
  PerspectiveCamera() = default;
  explicit PerspectiveCamera(const CameraDesc& desc);

  // Ray through image position `pixelPos` (continuous, in pixels: (0,0) top-left corner).
  Ray generateRay(Vec2 pixelPos) const {
    float sx = pixelPos.x * invWidth_, sy = pixelPos.y * invHeight_;
    float x = (1.f - 2.f * sx) * tanHalfX_, y = (1.f - 2.f * sy) * tanHalfY_;
    // The camera basis is orthonormal: |x right + y up + forward| = |(x, y, 1)|.
    float len = std::sqrt(x * x + y * y + 1.f);
    Ray ray;
    ray.o = origin_;
    ray.d = (right_ * x + up_ * y + forward_) * (1.f / len);
    ray.tMin = desc_.nearClip * len;  // clip planes are perpendicular to the view axis
    ray.tMax = desc_.farClip * len;
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
  const Vec3& right() const { return right_; }
  const Vec3& up() const { return up_; }
  // generateRay's constants: tan of the half field of view per axis, 1 / the image's size.
  Vec2 tanHalfFov() const { return Vec2(tanHalfX_, tanHalfY_); }
  Vec2 inverseSize() const { return Vec2(invWidth_, invHeight_); }

 private:
  CameraDesc desc_;
  Vec3 origin_{0.f}, right_{1, 0, 0}, up_{0, 1, 0}, forward_{0, 0, 1};  // right_ is camera +x (left)
  float tanHalfX_ = 0.f, tanHalfY_ = 0.f, invWidth_ = 0.f, invHeight_ = 0.f;
};

}  // namespace penumbra
