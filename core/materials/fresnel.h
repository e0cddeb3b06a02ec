// The unpolarised Fresnel reflectance of a smooth dielectric interface.
#pragma once

#include <cmath>

namespace penumbra {

// Reflectance for light arriving at cosine cosI (> 0) to the interface normal from the side of index
// extIOR onto index intIOR: the mean of the s- and p-polarised reflectances (Fresnel's equations),
// 1 under total internal reflection, 0 when the indices are equal.
inline float fresnelDielectric(float cosI, float extIOR, float intIOR) {
  if (extIOR == intIOR) return 0.f;   // no interface (exactly, where cos θt would round away from cos θi)
  const float eta = extIOR / intIOR;  // n1 / n2
  const float sin2T = eta * eta * std::fmax(0.f, 1.f - cosI * cosI);
  if (sin2T >= 1.f) return 1.f;
  const float cosT = std::sqrt(1.f - sin2T);
  const float rs = (extIOR * cosI - intIOR * cosT) / (extIOR * cosI + intIOR * cosT);
  const float rp = (intIOR * cosI - extIOR * cosT) / (intIOR * cosI + extIOR * cosT);
  return 0.5f * (rs * rs + rp * rp);
}

}  // namespace penumbra
