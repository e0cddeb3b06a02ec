// Vector types and constants shared by all of core. Geometry is float; accumulation is double.
#pragma once

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>

namespace penumbra {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Color3 = glm::vec3;
using IVec2 = glm::ivec2;
using DVec3 = glm::dvec3;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr double kPiD = 3.14159265358979323846;  // double-precision paths (pdfs, closed forms)
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;
inline constexpr float kPiOver2 = 1.57079632679489661923f;
inline constexpr float kPiOver4 = 0.78539816339744830962f;
// Largest float below 1: samplers never hand out 1.0 (1 - 2^-24).
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

inline float maxComponent(const Vec3& v) {
  return glm::max(v.x, glm::max(v.y, v.z));
}
// Component-wise |v| with std::fabs: one AND per component (glm::abs compiles to compare-and-select,
// because it must keep x >= 0 ? x : -x semantics for -0). Used on the per-ray paths.
inline Vec3 absVec(const Vec3& v) {
  return Vec3(std::fabs(v.x), std::fabs(v.y), std::fabs(v.z));
}
inline float maxAbsComponent(const Vec3& v) {
  return maxComponent(absVec(v));
}
inline float luminance(const Color3& c) {
  return 0.212671f * c.x + 0.715160f * c.y + 0.072169f * c.z;
}
inline bool isBlack(const Color3& c) {
  return c.x == 0.f && c.y == 0.f && c.z == 0.f;
}

}  // namespace penumbra
