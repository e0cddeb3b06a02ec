// Area-light sampling of the packet kernels, lane by lane as the lights compute it: sphere lights by
// area and solid angle (SphereLight), polygon lights by area (PolygonLight).
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_LIGHTS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_LIGHTS_INL_H_
#undef PENUMBRA_PACKET_LIGHTS_INL_H_
#else
#define PENUMBRA_PACKET_LIGHTS_INL_H_
#endif

#include <hwy/highway.h>

#include <cfloat>
#include <vector>

#include "core/lights/sphere_light.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_math-inl.h"
#include "core/render/packet_scene.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// A light sample for every lane: the lanes where it is valid with a positive pdf and radiance; for
// projected-solid-angle samples also the estimate factor cos θ / pdf they carry instead of the quotient
// (the Ω⊥ of LightTechnique's cosOverPdf).
struct PacketLightSample {
  MF valid;
  V3F wi;
  VF dist, pdf;
  VF projected;
};

// LightTechnique::cosOverPdf of the measure.
template <LightMeasure kMeasure>
HWY_INLINE VF cosOverPdf(const PacketLightSample& s, VF cosTheta) {
  if constexpr (kMeasure == LightMeasure::ProjectedSolidAngle) return s.projected;
  return cosTheta / s.pdf;
}
// LightTechnique::cosOverSelectedPdf of the measure, for a light picked with probability pmf.
template <LightMeasure kMeasure>
HWY_INLINE VF cosOverSelectedPdf(const PacketLightSample& s, VF cosTheta, VD pmf) {
  if constexpr (kMeasure == LightMeasure::ProjectedSolidAngle) return demote(promote(s.projected) / pmf);
  return demote(promote(cosTheta) / (promote(s.pdf) * pmf));
}

// SphereLight::sampleArea (with Warp::squareToUniformSphere).
HWY_INLINE PacketLightSample sampleArea(const PacketLight& light, const V3F& x, VF u0, VF u1) {
  const DF df;
  const DD dd;
  const VF w = setF(2.f) * u0;
  const VF s2 = w * (setF(2.f) - w);
  const VF sinTheta = hn::Sqrt(hn::IfThenElse(s2 < hn::Zero(df), hn::Zero(df), s2));
  VF sinPhi, cosPhi;
  sinCosTurns(u1, sinPhi, cosPhi);
  const V3F n{sinTheta * cosPhi, sinTheta * sinPhi, setF(1.f) - w};
  const VF r = setF(light.radius);
  const V3F p{setF(light.center[0]) + r * n.x, setF(light.center[1]) + r * n.y,
              setF(light.center[2]) + r * n.z};
  const V3D xD = promote(x), pD = promote(p);
  const V3D toP{pD.x - xD.x, pD.y - xD.y, pD.z - xD.z};
  const VD dist2 = dot(toP, toP);
  const VD nDotToP = dot(promote(n), toP);
  const VD zero = hn::Zero(dd);
  const VD dist = hn::Sqrt(dist2);
  const VD invDist = setD(1.0) / dist;
  const double fourPiR2 = 4.0 * kPiD * double(light.radius) * light.radius;
  const VD pdf = dist2 * dist / (setD(fourPiR2) * hn::Abs(nDotToP));
  // Far-side points (n·toP ≥ 0) have Le = 0: skipped as the scalar loop skips black samples.
  const MD valid = hn::And(hn::And(dist2 > zero, nDotToP < zero), pdf <= setD(SphereLight::kMaxPdf));
  PacketLightSample s;
  s.pdf = demote(pdf);
  s.valid = hn::And(toF(valid), s.pdf > hn::Zero(df));
  s.wi = demote(V3D{toP.x * invDist, toP.y * invDist, toP.z * invDist});
  s.dist = demote(dist);
  s.projected = hn::Zero(df);
  return s;
}

// subtendedCone (sphere_light.cpp): the cone the light subtends at x, valid where x is outside the
// sphere at a finite distance and the cone's pdf fits a float.
struct ConeD {
  V3D wc;
  VD d, sin2Max, oneMinusCos;
  MD valid;
};
HWY_INLINE ConeD subtendedCone(const PacketLight& light, const V3D& x) {
  const double r = light.radius;
  const V3D dc{setD(double(light.center[0])) - x.x, setD(double(light.center[1])) - x.y,
               setD(double(light.center[2])) - x.z};
  ConeD c;
  c.d = hn::Sqrt(dot(dc, dc));
  const VD invD = setD(1.0) / c.d;
  c.wc = {dc.x * invD, dc.y * invD, dc.z * invD};
  const VD sinMax = setD(r) * invD;
  c.sin2Max = sinMax * sinMax;
  const VD cosMax = hn::Sqrt((c.d - setD(r)) * (c.d + setD(r))) * invD;
  c.oneMinusCos = c.sin2Max / (setD(1.0) + cosMax);
  c.valid = hn::And(hn::And(c.d >= setD(r), c.d < setD(INFINITY)),
                    c.oneMinusCos >= setD(SphereLight::kMinOneMinusCos));
  return c;
}

// SphereLight::sampleSolidAngle (with orthonormalBasis).
HWY_INLINE PacketLightSample sampleSolidAngle(const PacketLight& light, const V3F& x, VF u0, VF u1) {
  const DD dd;
  const double r = light.radius;
  const V3D xD = promote(x);
  const ConeD cone = subtendedCone(light, xD);
  const V3D& wc = cone.wc;
  const VD& d = cone.d;
  const VD& oneMinusCos = cone.oneMinusCos;
  const MD valid = cone.valid;

  const VD oneMinusCosT = promote(u0) * oneMinusCos;
  const VD cosT = setD(1.0) - oneMinusCosT;
  const VD sin2T = oneMinusCosT * (setD(2.0) - oneMinusCosT);
  const VD sinT = hn::Sqrt(sin2T);
  VF sinPhiF, cosPhiF;
  sinCosTurns(u1, sinPhiF, cosPhiF);
  const VD cosPhi = promote(cosPhiF), sinPhi = promote(sinPhiF);
  const VD invSinMax = d / setD(r);
  const VD ratio = sin2T * invSinMax;
  const VD zero = hn::Zero(dd);
  // std::max(0.0, v): NaN goes to 0 as there.
  auto clampPositive = [&](VD v) { return hn::IfThenElse(zero < v, v, zero); };
  const VD cosA = ratio + cosT * hn::Sqrt(clampPositive(setD(1.0) - ratio * invSinMax));
  const VD sinA = hn::Sqrt(clampPositive(setD(1.0) - cosA * cosA));
  // orthonormalBasis(wc, s, t).
  const VD sign = hn::CopySign(setD(1.0), wc.z);
  const VD a = setD(-1.0) / (sign + wc.z);
  const VD b = wc.x * wc.y * a;
  const V3D s{setD(1.0) + sign * wc.x * wc.x * a, sign * b, hn::Neg(sign) * wc.x};
  const V3D t{b, sign + wc.y * wc.y * a, hn::Neg(wc.y)};
  const V3D lateral{cosPhi * s.x + sinPhi * t.x, cosPhi * s.y + sinPhi * t.y, cosPhi * s.z + sinPhi * t.z};
  const V3D wi{sinT * lateral.x + cosT * wc.x, sinT * lateral.y + cosT * wc.y,
               sinT * lateral.z + cosT * wc.z};
  const V3D n{sinA * lateral.x - cosA * wc.x, sinA * lateral.y - cosA * wc.y, sinA * lateral.z - cosA * wc.z};
  const VD rD = setD(r);
  const V3D p{setD(double(light.center[0])) + rD * n.x, setD(double(light.center[1])) + rD * n.y,
              setD(double(light.center[2])) + rD * n.z};
  const V3D toP{p.x - xD.x, p.y - xD.y, p.z - xD.z};
  PacketLightSample out;
  out.wi = demote(wi);
  out.dist = demote(hn::Sqrt(dot(toP, toP)));
  out.pdf = demote(setD(1.0) / (setD(2.0 * kPiD) * oneMinusCos));
  out.valid = hn::And(toF(valid), out.pdf > hn::Zero(DF()));
  out.projected = hn::Zero(DF());
  return out;
}

// SphereLight::pdfAreaAsSolidAngle: the density of area sampling reaching point p (normal n) from x.
HWY_INLINE VF pdfAreaAsSolidAngle(const PacketLight& light, const V3F& x, const V3F& p, const V3F& n) {
  const DD dd;
  const V3D xD = promote(x), pD = promote(p);
  const V3D toX{xD.x - pD.x, xD.y - pD.y, xD.z - pD.z};
  const VD d2 = dot(toX, toX);
  const VD zero = hn::Zero(dd);
  const VD cosP = dot(promote(n), toX) / hn::Sqrt(d2);
  const double fourPiR2 = 4.0 * kPiD * double(light.radius) * light.radius;
  const VD pdf = d2 / (setD(fourPiR2) * hn::Abs(cosP));
  const MD valid = hn::And(hn::And(d2 > zero, cosP != zero), pdf <= setD(SphereLight::kMaxPdf));
  return demote(hn::IfThenElseZero(valid, pdf));
}

// SphereLight::pdfSolidAngle: the density of cone sampling producing unit direction w at x.
HWY_INLINE VF pdfSolidAngle(const PacketLight& light, const V3F& x, const V3F& wF) {
  const ConeD cone = subtendedCone(light, promote(x));
  const V3D w = promote(wF);
  const VD zero = hn::Zero(DD());
  const VD cosW = dot(w, cone.wc);
  const V3D c = cross(w, cone.wc);
  const VD sin2W = dot(c, c) / dot(w, w);
  // Inside the cone up to the rounding of a float direction (kDirectionSlack).
  const VD sinMax = hn::Sqrt(cone.sin2Max) + setD(SphereLight::kDirectionSlack);
  const MD inside = hn::And(hn::AndNot(cosW <= zero, cone.valid), hn::Not(sin2W > sinMax * sinMax));
  return demote(hn::IfThenElseZero(inside, setD(1.0) / (setD(2.0 * kPiD) * cone.oneMinusCos)));
}

// Polygon lights in lanes: one light broadcast, or each lane its own.
struct PolygonLanes {
  V3F p0, e1, e2, n;
  VF area, scale;
  MF parallelogram;
  V3F radiance;
};

HWY_INLINE PolygonLanes broadcast(const PacketPolygonLight& l) {
  return {setF3(l.p0),
          setF3(l.e1),
          setF3(l.e2),
          setF3(l.n),
          setF(l.area),
          setF(l.scale),
          hn::Ne(setF(l.parallelogram ? 1.f : 0.f), hn::Zero(DF())),
          setF3(l.radiance)};
}

// Each lane's polygon light: `index` into PacketScene::polygons where >= 0, a placeholder elsewhere.
HWY_INLINE PolygonLanes gatherPolygons(const std::vector<PacketPolygonLight>& polygons, const float* index) {
  const DF df;
  const size_t lanes = hn::Lanes(df);
  alignas(64) float v[18][kMaxPacketLanes];
  for (size_t k = 0; k < lanes; ++k) {
    const PacketPolygonLight& l = polygons[index[k] >= 0.f ? size_t(index[k]) : 0];
    for (int c = 0; c < 3; ++c) {
      v[c][k] = l.p0[c], v[3 + c][k] = l.e1[c], v[6 + c][k] = l.e2[c], v[9 + c][k] = l.n[c];
      v[14 + c][k] = l.radiance[c];
    }
    v[12][k] = l.area, v[13][k] = l.scale, v[17][k] = l.parallelogram ? 1.f : 0.f;
  }
  auto load3 = [&](int c) { return V3F{hn::Load(df, v[c]), hn::Load(df, v[c + 1]), hn::Load(df, v[c + 2])}; };
  return {load3(0),
          load3(3),
          load3(6),
          load3(9),
          hn::Load(df, v[12]),
          hn::Load(df, v[13]),
          hn::Ne(hn::Load(df, v[17]), hn::Zero(df)),
          load3(14)};
}

// PolygonLight::faces: x above the light's plane by more than 2^-20 of the coordinates' magnitude.
HWY_INLINE MD faces(const PolygonLanes& light, const V3F& x) {
  const VD margin = setD(0x1p-20) * promote(maxOf(light.scale, maxAbs(x)));
  return dot(promote(light.n), minus(promote(x), promote(light.p0))) > margin;
}
// The lanes of m whose light a direction map can sample from x: light.valid() and light.faces(x).
HWY_INLINE MD validAndFacing(const PolygonLanes& light, const V3F& x, MF m) {
  return hn::And(toD(hn::And(m, light.area > hn::Zero(DF()))), faces(light, x));
}

// PolygonLight::sampleArea: a uniform point (Heitz's triangle map on triangles), its solid-angle
// density d² / (area |cos θp|) in double (areaDensityAsSolidAngle), valid where x faces the light.
HWY_INLINE PacketLightSample samplePolygonArea(const PolygonLanes& light, const V3F& x, VF u0, VF u1) {
  const DD dd;
  const VD zero = hn::Zero(dd);
  VD a = promote(u0), b = promote(u1);
  const VD aHalf = a * setD(0.5), bHalf = b * setD(0.5);
  const MD above = b > a;
  const MD triangle = toD(hn::Not(light.parallelogram));
  const VD aT = hn::IfThenElse(above, aHalf, a - bHalf), bT = hn::IfThenElse(above, b - aHalf, bHalf);
  a = hn::IfThenElse(triangle, aT, a);
  b = hn::IfThenElse(triangle, bT, b);
  const V3D p0 = promote(light.p0), e1 = promote(light.e1), e2 = promote(light.e2), n = promote(light.n);
  const V3D p{p0.x + a * e1.x + b * e2.x, p0.y + a * e1.y + b * e2.y, p0.z + a * e1.z + b * e2.z};
  const V3D xD = promote(x);
  const V3D d{p.x - xD.x, p.y - xD.y, p.z - xD.z};
  const VD d2 = dot(d, d);
  const VD dist = hn::Sqrt(d2);
  const VD cosArea = hn::Abs(dot(n, d)) * promote(light.area);
  const VD pdf = d2 * dist / cosArea;
  const MD finite = hn::And(cosArea > zero, pdf < setD(double(FLT_MAX)));
  PacketLightSample s;
  s.pdf = demote(hn::IfThenElseZero(finite, pdf));
  s.valid = hn::And(toF(faces(light, x)), s.pdf > hn::Zero(DF()));
  s.wi = demote(V3D{d.x / dist, d.y / dist, d.z / dist});
  s.dist = demote(dist);
  s.projected = hn::Zero(DF());
  return s;
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
