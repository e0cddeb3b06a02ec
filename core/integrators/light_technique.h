// The light-sampling techniques of `direct`, one per measure and light type (here the sphere's;
// polygon_light_technique.h has the polygon's), for one light seen from one shading point: how a direction
// towards the light is sampled, the factor cos θ / pdf its estimate carries (cosOverPdf; cosOverSelectedPdf
// when the light was chosen with probability pmf), and the solid-angle density with which the technique
// produces a given direction that reaches the light (MIS weighs directions the other technique sampled with
// it).
#pragma once

#include <cstdint>

#include "core/integrators/integrator_desc.h"
#include "core/integrators/shading_point.h"
#include "core/lights/projected_cap.h"
#include "core/lights/sphere_light.h"

namespace penumbra {

template <LightMeasure kMeasure, class Light>
class LightTechnique;

// A uniform point on the whole sphere; far-side points are samples with Le = 0.
template <>
class LightTechnique<LightMeasure::Area, SphereLight> {
 public:
  LightTechnique(const SphereLight& light, const ShadingPoint& sp) : light_(light), x_(sp.hit.p) {}
  bool canSample() const { return true; }
  LightSample sample(Vec2 u) const { return light_.sampleArea(x_, u); }
  float cosOverPdf(const LightSample& s, float cosTheta) const { return cosTheta / s.pdf; }
  // Divided in double: the pmfs of many lights are tiny.
  double cosOverSelectedPdf(const LightSample& s, float cosTheta, double pmf) const {
    return double(cosTheta) / (double(s.pdf) * pmf);
  }
  // The density of reaching the light at p (normal n), the first point a direction from x meets.
  float pdf(const Vec3& /*w*/, const Vec3& p, const Vec3& n) const {
    return light_.pdfAreaAsSolidAngle(x_, p, n);
  }

 private:
  const SphereLight& light_;
  Vec3 x_;
};

// A uniform direction in the cone the sphere subtends.
template <>
class LightTechnique<LightMeasure::SolidAngle, SphereLight> {
 public:
  LightTechnique(const SphereLight& light, const ShadingPoint& sp) : light_(light), x_(sp.hit.p) {}
  bool canSample() const { return true; }
  LightSample sample(Vec2 u) const { return light_.sampleSolidAngle(x_, u); }
  float cosOverPdf(const LightSample& s, float cosTheta) const { return cosTheta / s.pdf; }
  double cosOverSelectedPdf(const LightSample& s, float cosTheta, double pmf) const {
    return double(cosTheta) / (double(s.pdf) * pmf);
  }
  float pdf(const Vec3& w, const Vec3& /*p*/, const Vec3& /*n*/) const { return light_.pdfSolidAngle(x_, w); }

 private:
  const SphereLight& light_;
  Vec3 x_;
};

// A direction in the subtended cone with density cos θ / Ω⊥ above the horizon of the shading normal:
// cos θ / pdf is Ω⊥ for every sample, in closed form.
template <>
class LightTechnique<LightMeasure::ProjectedSolidAngle, SphereLight> {
 public:
  LightTechnique(const SphereLight& light, const ShadingPoint& sp) {
    valid_ = cap_.init(light, sp.hit.p, sp.ns);
    projectedSolidAngle_ = static_cast<float>(cap_.projectedSolidAngle);
  }
  bool canSample() const { return valid_; }
  LightSample sample(Vec2 u) const { return cap_.sample(u); }
  float cosOverPdf(const LightSample& /*s*/, float /*cosTheta*/) const { return projectedSolidAngle_; }
  // The closed form kept: no variance from a division by the sample's pdf.
  double cosOverSelectedPdf(const LightSample& /*s*/, float /*cosTheta*/, double pmf) const {
    return double(projectedSolidAngle_) / pmf;
  }
  float pdf(const Vec3& w, const Vec3& /*p*/, const Vec3& /*n*/) const { return valid_ ? cap_.pdf(w) : 0.f; }

 private:
  ProjectedSphereCap cap_;
  float projectedSolidAngle_ = 0.f;
  bool valid_ = false;
};

}  // namespace penumbra
