// Orthonormal frame around a unit normal (Duff et al. 2017, branchless and continuous except at n.z = -1).
#pragma once

#include "core/math/vec.h"

namespace penumbra {

struct Frame {
  Vec3 s, t, n;

  Frame() : s(1, 0, 0), t(0, 1, 0), n(0, 0, 1) {}
  explicit Frame(const Vec3& normal) : n(normal) {
    float sign = std::copysign(1.f, n.z);
    float a = -1.f / (sign + n.z);
    float b = n.x * n.y * a;
    s = Vec3(1.f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    t = Vec3(b, sign + n.y * n.y * a, -n.y);
  }

  Vec3 toWorld(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
  Vec3 toLocal(const Vec3& v) const { return Vec3(glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)); }
};

// The same basis around a unit double vector (light sampling builds its frames in double).
inline void orthonormalBasis(const DVec3& n, DVec3& s, DVec3& t) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  s = DVec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  t = DVec3(b, sign + n.y * n.y * a, -n.y);
}

}  // namespace penumbra

#include <glm/mat4x4.hpp>

namespace penumbra {

// Nori's camera-to-world matrix: columns (left, up, dir, origin); the camera looks down +z.
inline glm::mat4 cameraToWorld(const Vec3& origin, const Vec3& left, const Vec3& up, const Vec3& dir) {
  glm::mat4 m(1.f);
  m[0] = glm::vec4(left, 0.f);
  m[1] = glm::vec4(up, 0.f);
  m[2] = glm::vec4(dir, 0.f);
  m[3] = glm::vec4(origin, 1.f);
  return m;
}

}  // namespace penumbra
