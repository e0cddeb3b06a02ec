// The light-sampling techniques of polygon lights in the packet kernels (LightTechnique<measure,
// PolygonLight> in lanes), of one light broadcast to every lane or of each lane's own: by area in lanes
// (samplePolygonArea); triangles by the solid angle in lanes on Arvo's map (SphericalTriangle mirrored
// operation by operation, libm's atan2, sin and cos called lane by lane); the rest (parallelograms by the
// solid angle, triangles too small for the map, every polygon by the projected solid angle) by the
// scalar techniques lane by lane (ScalarLightSamples), the rest of each draw (shadow ray, reflection,
// weights, sums) in lanes.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_POLYGON_TECHNIQUES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_POLYGON_TECHNIQUES_INL_H_
#undef PENUMBRA_PACKET_POLYGON_TECHNIQUES_INL_H_
#else
#define PENUMBRA_PACKET_POLYGON_TECHNIQUES_INL_H_
#endif

#include <hwy/highway.h>

#include <cfloat>
#include <cmath>

#include "core/lights/spherical_triangle.h"

#include "core/render/packet_bsdf-inl.h"
#include "core/render/packet_geometry-inl.h"
#include "core/render/packet_lights-inl.h"
#include "core/render/packet_math-inl.h"
#include "core/render/packet_scalar_samples-inl.h"
#include "core/render/packet_scene.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

HWY_INLINE V3D minus(const V3D& a, const V3D& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
HWY_INLINE V3D plus(const V3D& a, const V3D& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
// s · v (glm's scalar times vector).
HWY_INLINE V3D times(VD s, const V3D& v) {
  return {s * v.x, s * v.y, s * v.z};
}

// SphericalTriangle::init (Arvo's map) of each lane's triangle light seen from x, as PolygonSolidAngle
// sets it up, in the lanes of m: inLanes where the map samples it; byArea where its solid angle is below
// SphericalTriangle::kMinSolidAngle (left to the scalar technique); neither where it cannot be sampled
// (x behind it or in its plane, degenerate).
struct SphericalTriangleLanes {
  V3D origin, a, b, cPerp;
  V3D edgeNormals[3];
  VD solidAngle, alpha, sinAlpha, cosAlpha, cosC;
  MD inLanes, byArea;
};

HWY_INLINE SphericalTriangleLanes sphericalTriangle(const PolygonLanes& light, const V3F& x, MF m) {
  const DD dd;
  const VD zero = hn::Zero(dd), one = setD(1.0);
  SphericalTriangleLanes t;
  // PolygonSolidAngle::init: light.valid() (area > 0) and light.faces(x); the vertices in float.
  const V3D p0 = promote(light.p0);
  const V3D v1 = promote(V3F{light.p0.x + light.e1.x, light.p0.y + light.e1.y, light.p0.z + light.e1.z});
  const V3D v2 = promote(V3F{light.p0.x + light.e2.x, light.p0.y + light.e2.y, light.p0.z + light.e2.z});
  t.origin = promote(x);
  const VD margin = setD(0x1p-20) * promote(maxOf(light.scale, maxAbs(x)));
  MD ok = hn::And(toD(hn::And(m, light.area > hn::Zero(DF()))),
                  dot(promote(light.n), minus(t.origin, p0)) > margin);
  const V3D e1 = minus(v1, p0), e2 = minus(v2, p0);
  const V3D n = cross(e1, e2);
  const VD twiceArea = hn::Sqrt(dot(n, n));
  ok = hn::And(ok, hn::And(twiceArea > zero, twiceArea < setD(INFINITY)));
  const V3D d0 = minus(p0, t.origin), d1 = plus(d0, e1), d2 = plus(d0, e2);
  const VD l0 = hn::Sqrt(dot(d0, d0)), l1 = hn::Sqrt(dot(d1, d1)), l2 = hn::Sqrt(dot(d2, d2));
  const VD det = dot(d0, n), absDet = hn::Abs(det);
  ok = hn::And(ok, hn::And(absDet > setD(1e-12) * l0 * twiceArea, absDet < setD(INFINITY)));
  t.a = {d0.x / l0, d0.y / l0, d0.z / l0};
  t.b = {d1.x / l1, d1.y / l1, d1.z / l1};
  const V3D c{d2.x / l2, d2.y / l2, d2.z / l2};
  // Van Oosterom & Strackee: tan(Ω/2) = |a · (b × c)| / (1 + a·b + b·c + c·a).
  const VD tanNumerator = absDet / (l0 * l1 * l2);
  const VD tanDenominator = one + dot(t.a, t.b) + dot(t.b, c) + dot(c, t.a);
  t.solidAngle = setD(2.0) * libmLanes(ok, tanNumerator, tanDenominator,
                                       [](double y, double x) { return std::atan2(y, x); });
  const VD sign = hn::IfThenElse(det > zero, one, setD(-1.0));
  const V3D nab = cross(d0, e1), nac = cross(d0, e2);
  t.edgeNormals[0] = normalized(times(sign, nab));
  t.edgeNormals[1] = normalized(times(sign, cross(d1, minus(e2, e1))));
  t.edgeNormals[2] = normalized(times(hn::Neg(sign), nac));
  ok = hn::And(ok, t.solidAngle > zero);
  t.byArea = hn::And(ok, t.solidAngle < setD(SphericalTriangle::kMinSolidAngle));
  t.inLanes = hn::AndNot(t.byArea, ok);
  // The angle at a between the arcs to b and to c.
  t.alpha =
      libmLanes(t.inLanes, l0 * absDet, dot(nab, nac), [](double y, double x) { return std::atan2(y, x); });
  t.sinAlpha = libmLanes(t.inLanes, t.alpha, [](double v) { return std::sin(v); });
  t.cosAlpha = libmLanes(t.inLanes, t.alpha, [](double v) { return std::cos(v); });
  t.cosC = dot(t.a, t.b);
  t.cPerp = normalized(minus(e2, times(dot(e2, t.a), t.a)));
  return t;
}

// std::clamp(v, lo, hi): NaN kept.
HWY_INLINE VD clampD(VD v, VD lo, VD hi) {
  return hn::IfThenElse(v < lo, lo, hn::IfThenElse(hi < v, hi, v));
}
// std::sqrt(std::max(0.0, v)): NaN goes to 0 as there.
HWY_INLINE VD sqrtAtLeastZero(VD v) {
  const VD zero = hn::Zero(DD());
  return hn::Sqrt(hn::IfThenElse(zero < v, v, zero));
}

// SphericalTriangle::sampleDirection on Arvo's map, in the lanes of t.inLanes.
HWY_INLINE V3D sampleSphericalTriangle(const SphericalTriangleLanes& t, VF u0, VF u1) {
  const VD one = setD(1.0);
  const VD areaHat = promote(u0) * t.solidAngle;
  const VD angle = areaHat - t.alpha;
  const VD s = libmLanes(t.inLanes, angle, [](double v) { return std::sin(v); });
  const VD c = libmLanes(t.inLanes, angle, [](double v) { return std::cos(v); });
  const VD uu = c - t.cosAlpha, vv = s + t.sinAlpha * t.cosC;
  const VD q =
      clampD(((vv * c - uu * s) * t.cosAlpha - vv) / ((vv * s + uu * c) * t.sinAlpha), setD(-1.0), one);
  const V3D cHat = plus(times(q, t.a), times(sqrtAtLeastZero((one - q) * (one + q)), t.cPerp));
  // Then on the arc from b to ĉ, cos to b linear in u.y.
  const V3D toB = minus(cHat, t.b);
  const VD oneMinusZ = promote(u1) * setD(0.5) * dot(toB, toB);
  const VD z = one - oneMinusZ;
  const V3D side = minus(cHat, times(dot(cHat, t.b), t.b));
  const VD sideLength = hn::Sqrt(dot(side, side));
  const V3D w = normalized(
      plus(times(z, t.b), times(sqrtAtLeastZero(oneMinusZ * (one + z)),
                                V3D{side.x / sideLength, side.y / sideLength, side.z / sideLength})));
  return select(sideLength > hn::Zero(DD()), w, t.b);
}

// SphericalTriangle::pdfDirection of unit direction w where the map samples (1 / Ω inside the
// triangle, 0 outside), 0 in the other lanes.
HWY_INLINE VD pdfSphericalTriangle(const SphericalTriangleLanes& t, const V3D& w) {
  MD inside = t.inLanes;
  for (const V3D& m : t.edgeNormals) inside = hn::AndNot(dot(m, w) < setD(-1e-12), inside);
  return hn::IfThenElseZero(inside, setD(1.0) / t.solidAngle);
}

// PolygonLight::sampleAlong and the solid-angle technique's density: the sample of unit direction w
// from x towards the light (valid where it meets its plane in front of x and the density fits a float).
HWY_INLINE PacketLightSample sampleAlong(const PolygonLanes& light, const V3D& x, const V3D& w, VD pdf,
                                         MD m) {
  const V3D n = promote(light.n);
  const VD t = dot(n, minus(promote(light.p0), x)) / dot(n, w);
  const MD along = hn::And(m, hn::And(t > hn::Zero(DD()), t < setD(double(FLT_MAX))));
  PacketLightSample s;
  s.wi = demote(w);
  s.dist = demote(t);
  // floatDensity: 0 where it does not fit a float.
  const MD fits = hn::And(pdf > hn::Zero(DD()), pdf < setD(3.4e38));
  s.pdf = demote(hn::IfThenElseZero(hn::And(along, fits), pdf));
  s.valid = s.pdf > hn::Zero(DF());
  s.projected = hn::Zero(DF());
  return s;
}

// LightTechnique<kMeasure, PolygonLight> of the polygon light of each lane of `active` (`light`; `index`
// its index among the area lights, per lane) at the lanes' shading points, for draws before drawEnd:
// sample(draws, j) draws the light sample of draw j.
template <LightMeasure kMeasure>
struct PolygonTechnique {
  static constexpr bool kTriangleMap = kMeasure == LightMeasure::SolidAngle;
  const PolygonLanes& light;
  V3F x;
  SphericalTriangleLanes triangle;  // by the solid angle: the triangle lights' maps
  bool anyTriangle = false;
  ScalarLightSamples<kMeasure> scalar;

  PolygonTechnique(const PacketScene& scene, const PolygonLanes& l, const float* index, const PacketHit& h,
                   MF active, size_t drawEnd)
      : light(l), x(h.p), scalar(scene, index, h, byScalar(active), drawEnd) {}

  PacketLightSample sample(const PacketDraws& draws, size_t j) const {
    VF u0, u1;
    loadDraw(draws, j, u0, u1);
    if constexpr (kMeasure == LightMeasure::Area) return samplePolygonArea(light, x, u0, u1);
    const VF zero = hn::Zero(DF());
    PacketLightSample s{hn::FirstN(DF(), 0), V3F{zero, zero, zero}, zero, zero, zero};
    if (anyTriangle) {
      const V3D w = sampleSphericalTriangle(triangle, u0, u1);
      s = sampleAlong(light, triangle.origin, w, pdfSphericalTriangle(triangle, w), triangle.inLanes);
    }
    return scalar.merge(draws, j, s);
  }

 private:
  // The lanes the scalar technique samples; sets up the maps of the others.
  MF byScalar(MF active) {
    if constexpr (kMeasure == LightMeasure::Area) return hn::FirstN(DF(), 0);
    if constexpr (kTriangleMap) {
      const MF triangles = hn::AndNot(light.parallelogram, active);
      if (!hn::AllFalse(DF(), triangles)) {
        triangle = sphericalTriangle(light, x, triangles);
        anyTriangle = !hn::AllFalse(DD(), triangle.inLanes);
        return hn::Or(hn::And(active, light.parallelogram), toF(triangle.byArea));
      }
    }
    return active;
  }
};
}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
