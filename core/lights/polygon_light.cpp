#include "core/lights/polygon_light.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "core/math/float_util.h"

namespace penumbra {

PolygonLight PolygonLight::make(const Vec3& p0, const Vec3& e1, const Vec3& e2, bool parallelogram,
                                const Color3& radiance) {
  PolygonLight l;
  l.p0 = p0;
  l.e1 = e1;
  l.e2 = e2;
  l.parallelogram = parallelogram;
  l.radiance = radiance;
  const DVec3 c = glm::cross(DVec3(e1), DVec3(e2));
  const double twiceArea = glm::length(c);
  const double area = parallelogram ? twiceArea : 0.5 * twiceArea;
  if (!(twiceArea > 0.0) || !std::isfinite(twiceArea) || !(area < double(FLT_MAX)) || !isFinite(p0))
    return l;  // area 0: invalid
  l.n = Vec3(c / twiceArea);
  l.area = float(area);
  if (!(l.area > 0.f)) return l;
  Vec3 v[4];
  l.vertices(v);
  for (int i = 0; i < l.vertexCount(); ++i) l.scale = std::max(l.scale, maxAbsComponent(v[i]));
  return l;
}

void PolygonLight::vertices(Vec3 out[4]) const {
  out[0] = p0;
  out[1] = p0 + e1;
  if (parallelogram) {
    out[2] = p0 + e1 + e2;
    out[3] = p0 + e2;
  } else {
    out[2] = p0 + e2;
  }
}

Bounds PolygonLight::bounds() const {
  Vec3 v[4];
  vertices(v);
  Bounds b;
  for (int i = 0; i < vertexCount(); ++i) b.expand(v[i]);
  return b;
}

Vec3 PolygonLight::centroid() const {
  return p0 + (parallelogram ? 0.5f : 1.f / 3.f) * (e1 + e2);
}

bool PolygonLight::faces(const Vec3& x) const {
  const double margin = 0x1p-20 * std::max(double(scale), double(maxAbsComponent(x)));
  return glm::dot(DVec3(n), DVec3(x) - DVec3(p0)) > margin;
}

namespace {

// The solid-angle density d² / (area |cos θp|) = d³ / (area |n · (p − x)|) of a uniform area sample at
// p seen from x, or 0 when it is not a finite positive float.
float areaDensityAsSolidAngle(const DVec3& toPoint, const Vec3& n, float area) {
  const double d2 = glm::dot(toPoint, toPoint);
  const double cosArea = std::abs(glm::dot(DVec3(n), toPoint)) * double(area);
  if (!(cosArea > 0.0)) return 0.f;
  const double pdf = d2 * std::sqrt(d2) / cosArea;
  return pdf < double(FLT_MAX) ? float(pdf) : 0.f;
}

}  // namespace

// Triangles by Heitz's low-distortion map from the square ("A Low-Distortion Map Between Triangle and
// Square", 2019): uniform, and neighbouring strata stay neighbours (unlike the square-root map).
LightSample PolygonLight::sampleArea(const Vec3& x, Vec2 u) const {
  LightSample s;
  if (!valid() || !faces(x)) return s;
  double a = u.x, b = u.y;
  if (!parallelogram) {
    if (b > a) {
      a *= 0.5;
      b -= a;
    } else {
      b *= 0.5;
      a -= b;
    }
  }
  const DVec3 p = DVec3(p0) + a * DVec3(e1) + b * DVec3(e2);
  const DVec3 d = p - DVec3(x);
  const double dist = glm::length(d);
  s.pdf = areaDensityAsSolidAngle(d, n, area);
  if (!(s.pdf > 0.f)) return s;
  s.p = Vec3(p);
  s.n = n;
  s.wi = Vec3(d / dist);
  s.dist = float(dist);
  s.Le = radiance;
  return s;
}

float PolygonLight::pdfAreaAsSolidAngle(const Vec3& x, const Vec3& p) const {
  if (!valid()) return 0.f;
  return areaDensityAsSolidAngle(DVec3(p) - DVec3(x), n, area);
}

LightSample PolygonLight::sampleAlong(const Vec3& x, const DVec3& w) const {
  LightSample s;
  const DVec3 nd(n);
  const double along = glm::dot(nd, w);
  const double t = glm::dot(nd, DVec3(p0) - DVec3(x)) / along;
  if (!(t > 0.0) || !(t < double(FLT_MAX))) return s;
  s.p = Vec3(DVec3(x) + t * w);
  s.n = n;
  s.wi = Vec3(w);
  s.dist = float(t);
  s.Le = radiance;
  s.pdf = 1.f;  // a placeholder for "valid": the caller sets the density
  return s;
}

double polygonLightPower(const PolygonLight& light) {
  const double meanRadiance = (double(light.radiance.x) + light.radiance.y + light.radiance.z) / 3.0;
  const double power = 3.14159265358979323846 * double(light.area) * meanRadiance;
  return std::isfinite(power) && power > 0.0 ? power : 0.0;
}

}  // namespace penumbra
