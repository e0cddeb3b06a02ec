// The light-sampling techniques of `direct` for one polygon light (a triangle or a parallelogram)
// seen from one shading point, one per measure, with the sphere's interface (light_technique.h):
//   area: a uniform point on the polygon, density d² / (A |cos θp|);
//   solid angle: a uniform direction in the polygon's spherical triangle or rectangle;
//   projected solid angle: a direction with density cos θ / Ω⊥ over the polygon clipped to the
//   shading normal's horizon, so that cos θ / pdf is Ω⊥ for every sample (Lambert's closed form).
// A shading point behind the light's plane gets no sample from any of them (the light is one-sided).
#pragma once

#include "core/integrators/light_technique.h"
#include "core/lights/polygon_light.h"
#include "core/lights/polygon_solid_angle.h"
#include "core/lights/projected_polygon.h"

namespace penumbra {

template <>
class LightTechnique<LightMeasure::Area, PolygonLight> {
 public:
  LightTechnique(const PolygonLight& light, const ShadingPoint& sp) : light_(light), x_(sp.hit.p) {}
  bool canSample() const { return true; }
  LightSample sample(Vec2 u) const { return light_.sampleArea(x_, u); }
  float cosOverPdf(const LightSample& s, float cosTheta) const { return cosTheta / s.pdf; }
  double cosOverSelectedPdf(const LightSample& s, float cosTheta, double pmf) const {
    return double(cosTheta) / (double(s.pdf) * pmf);
  }
  float pdf(const Vec3& /*w*/, const Vec3& p, const Vec3& /*n*/) const {
    return light_.pdfAreaAsSolidAngle(x_, p);
  }

 private:
  const PolygonLight& light_;
  Vec3 x_;
};

template <>
class LightTechnique<LightMeasure::SolidAngle, PolygonLight> {
 public:
  LightTechnique(const PolygonLight& light, const ShadingPoint& sp) : light_(light), x_(sp.hit.p) {
    valid_ = map_.init(light, x_);
  }
  bool canSample() const { return valid_; }
  LightSample sample(Vec2 u) const {
    const DVec3 w = map_.sampleDirection(u);
    LightSample s = light_.sampleAlong(x_, w);
    if (s.pdf > 0.f) s.pdf = floatDensity(map_.pdfDirection(w));
    return s;
  }
  float cosOverPdf(const LightSample& s, float cosTheta) const { return cosTheta / s.pdf; }
  double cosOverSelectedPdf(const LightSample& s, float cosTheta, double pmf) const {
    return double(cosTheta) / (double(s.pdf) * pmf);
  }
  float pdf(const Vec3& w, const Vec3& /*p*/, const Vec3& /*n*/) const {
    return valid_ ? floatDensity(map_.pdfDirection(DVec3(w))) : 0.f;
  }

 private:
  // A density as a float: 0 (no sample) when it does not fit.
  static float floatDensity(double pdf) { return pdf > 0.0 && pdf < 3.4e38 ? float(pdf) : 0.f; }

  const PolygonLight& light_;
  Vec3 x_;
  PolygonSolidAngle map_;
  bool valid_ = false;
};

template <>
class LightTechnique<LightMeasure::ProjectedSolidAngle, PolygonLight> {
 public:
  LightTechnique(const PolygonLight& light, const ShadingPoint& sp) : light_(light), x_(sp.hit.p) {
    if (!light.valid() || !light.faces(x_)) return;
    Vec3 v[4];
    light.vertices(v);
    valid_ = map_.init(v, light.vertexCount(), x_, sp.ns);
    projectedSolidAngle_ = static_cast<float>(map_.projectedSolidAngle);
    valid_ = valid_ && projectedSolidAngle_ > 0.f;
  }
  bool canSample() const { return valid_; }
  LightSample sample(Vec2 u) const {
    const DVec3 w = map_.sampleDirection(u);
    LightSample s = light_.sampleAlong(x_, w);
    // The density of the map's own sample, cos θ / Ω⊥, without its inside test.
    const double pdf = glm::dot(w, map_.ez) / map_.projectedSolidAngle;
    if (s.pdf > 0.f) s.pdf = pdf > 0.0 && pdf < 3.4e38 ? float(pdf) : 0.f;
    return s;
  }
  float cosOverPdf(const LightSample& /*s*/, float /*cosTheta*/) const { return projectedSolidAngle_; }
  // The closed form kept: no variance from a division by the sample's pdf.
  double cosOverSelectedPdf(const LightSample& /*s*/, float /*cosTheta*/, double pmf) const {
    return double(projectedSolidAngle_) / pmf;
  }
  float pdf(const Vec3& w, const Vec3& /*p*/, const Vec3& /*n*/) const {
    if (!valid_) return 0.f;
    const double pdf = map_.pdfDirection(DVec3(w));
    return pdf > 0.0 && pdf < 3.4e38 ? float(pdf) : 0.f;
  }

 private:
  const PolygonLight& light_;
  Vec3 x_;
  ProjectedPolygon map_;
  float projectedSolidAngle_ = 0.f;
  bool valid_ = false;
};

}  // namespace penumbra
