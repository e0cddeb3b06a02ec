// Microfacet normal distributions (Beckmann, GGX) with their Smith-style masking terms and normal
// sampling, for unit vectors in the local frame (normal +z). Walter et al. 2007, "Microfacet Models for
// Refraction through Rough Surfaces", gives D and G1 of both; Heitz 2018, "Sampling the GGX Distribution
// of Visible Normals", the GGX visible-normal sampling.
#pragma once

#include <cmath>

#include "core/materials/bsdf.h"
#include "core/math/vec.h"
#include "core/sampling/warp.h"

namespace penumbra {

// D(h), normalised so that ∫ D(h) cos θh dω = 1; 0 for h below the surface.
//   Beckmann: exp(-tan²θh/α²) / (π α² cos⁴θh);
//   GGX:      1 / (π α² cos⁴θh (1 + tan²θh/α²)²) = α² / (π (sin²θh + α² cos²θh)²) (the form without
//             cancellation near the normal).
inline float microfacetD(MicrofacetDistribution dist, const Vec3& h, float alpha) {
  const float c2 = h.z * h.z, s2 = h.x * h.x + h.y * h.y, a2 = alpha * alpha;
  if (!(h.z > 0.f)) return 0.f;
  if (dist == MicrofacetDistribution::Beckmann) {
    const float e = s2 / (c2 * a2);
    if (!(e < 87.f)) return 0.f;  // exp(-e) underflows; also avoids 0/0 when cos⁴θh does
    return std::exp(-e) / (kPi * a2 * c2 * c2);
  }
  const float d = s2 + a2 * c2;
  return a2 / (kPi * d * d);
}

// G1(v, h): 0 when v sees the back of the microfacet or of the surface ((v·h)(v·n) ≤ 0), else
//   Beckmann: Walter et al.'s rational fit, b = 1/(α tan θv): (3.535b + 2.181b²)/(1 + 2.276b + 2.577b²)
//             for b < 1.6, else 1;
//   GGX:      Smith's 2 / (1 + sqrt(1 + α² tan²θv)).
inline float microfacetG1(MicrofacetDistribution dist, const Vec3& v, const Vec3& h, float alpha) {
  if (!(glm::dot(v, h) * v.z > 0.f)) return 0.f;
  const float s2 = v.x * v.x + v.y * v.y, c2 = v.z * v.z;
  if (s2 == 0.f) return 1.f;
  if (dist == MicrofacetDistribution::Beckmann) {
    const float b = std::fabs(v.z) / (alpha * std::sqrt(s2));  // 1 / (α tan θv)
    if (b >= 1.6f) return 1.f;
    return (3.535f * b + 2.181f * b * b) / (1.f + 2.276f * b + 2.577f * b * b);
  }
  return 2.f / (1.f + std::sqrt(1.f + alpha * alpha * s2 / c2));
}

// Heitz 2018's visible GGX normal from wo (above the surface): density G1(wo,h) max(0, wo·h) D(h) / cos θo.
inline Vec3 sampleGgxVisibleNormal(const Vec3& wo, float alpha, Vec2 u) {
  const Vec3 vh = glm::normalize(Vec3(alpha * wo.x, alpha * wo.y, wo.z));  // wo on the hemisphere config.
  const float lensq = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = lensq > 0.f ? Vec3(-vh.y, vh.x, 0.f) * (1.f / std::sqrt(lensq)) : Vec3(1.f, 0.f, 0.f);
  const Vec3 t2 = glm::cross(vh, t1);
  const float r = std::sqrt(u.x), phi = 2.f * kPi * u.y;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.f + vh.z);
  const float p2 = (1.f - s) * std::sqrt(std::fmax(0.f, 1.f - p1 * p1)) + s * (r * std::sin(phi));
  const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::fmax(0.f, 1.f - p1 * p1 - p2 * p2));
  return glm::normalize(Vec3(alpha * nh.x, alpha * nh.y, std::fmax(0.f, nh.z)));
}

// The mirror reflection of v about the unit normal m.
inline Vec3 reflectAbout(const Vec3& v, const Vec3& m) {
  return m * (2.f * glm::dot(v, m)) - v;
}

}  // namespace penumbra
