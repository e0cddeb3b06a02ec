#include "core/render/camera.h"

#include <cmath>

namespace penumbra {

PerspectiveCamera::PerspectiveCamera(const CameraDesc& desc) : desc_(desc) {
  const glm::mat4& m = desc.toWorld;
  origin_ = Vec3(m[3]);
  // Columns may carry scale or shear: Gram-Schmidt them (keeping their orientation) so the basis is
  // orthonormal, which generateRay relies on.
  forward_ = glm::normalize(Vec3(m[2]));
  right_ = glm::normalize(Vec3(m[0]) - forward_ * glm::dot(Vec3(m[0]), forward_));
  up_ = glm::normalize(Vec3(m[1]) - forward_ * glm::dot(Vec3(m[1]), forward_) -
                       right_ * glm::dot(Vec3(m[1]), right_));
  float aspect = float(desc.width) / float(desc.height);
  tanHalfX_ = std::tan(glm::radians(desc.fovDegrees) * 0.5f);
  tanHalfY_ = tanHalfX_ / aspect;
  invWidth_ = 1.f / float(desc.width);
  invHeight_ = 1.f / float(desc.height);
}

bool PerspectiveCamera::project(const Vec3& worldDir, Vec2& pixelPos) const {
  float z = glm::dot(worldDir, forward_);
  if (!(z > 0.f)) return false;
  float x = glm::dot(worldDir, right_) / z, y = glm::dot(worldDir, up_) / z;
  pixelPos.x = (1.f - x / tanHalfX_) * 0.5f * float(desc_.width);
  pixelPos.y = (1.f - y / tanHalfY_) * 0.5f * float(desc_.height);
  return true;
}

}  // namespace penumbra
