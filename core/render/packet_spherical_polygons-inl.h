// The solid angle's maps of polygon lights in lanes: Arvo's spherical triangle and Ureña et al.'s
// spherical rectangle (SphericalTriangle, SphericalRectangle), set up, sampled and asked a sampled
// direction's density, mirrored operation by operation in double; libm's atan2, sin and cos are called
// lane by lane (libmLanes) on the lanes that need them.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_SPHERICAL_POLYGONS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_SPHERICAL_POLYGONS_INL_H_
#undef PENUMBRA_PACKET_SPHERICAL_POLYGONS_INL_H_
#else
#define PENUMBRA_PACKET_SPHERICAL_POLYGONS_INL_H_
#endif

#include <hwy/highway.h>

#include <cmath>

#include "core/lights/spherical_rectangle.h"
#include "core/lights/spherical_triangle.h"
#include "core/render/packet_lights-inl.h"
#include "core/render/packet_math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

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
  MD ok = validAndFacing(light, x, m);
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
  t.edgeNormals[0] = normalized(scaled(nab, sign));
  t.edgeNormals[1] = normalized(scaled(cross(d1, minus(e2, e1)), sign));
  t.edgeNormals[2] = normalized(scaled(nac, hn::Neg(sign)));
  ok = hn::And(ok, t.solidAngle > zero);
  t.byArea = hn::And(ok, t.solidAngle < setD(SphericalTriangle::kMinSolidAngle));
  t.inLanes = hn::AndNot(t.byArea, ok);
  // The angle at a between the arcs to b and to c.
  t.alpha =
      libmLanes(t.inLanes, l0 * absDet, dot(nab, nac), [](double y, double x) { return std::atan2(y, x); });
  t.sinAlpha = libmLanes(t.inLanes, t.alpha, [](double v) { return std::sin(v); });
  t.cosAlpha = libmLanes(t.inLanes, t.alpha, [](double v) { return std::cos(v); });
  t.cosC = dot(t.a, t.b);
  t.cPerp = normalized(minus(e2, scaled(t.a, dot(e2, t.a))));
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
  const V3D cHat = plus(scaled(t.a, q), scaled(t.cPerp, sqrtAtLeastZero((one - q) * (one + q))));
  // Then on the arc from b to ĉ, cos to b linear in u.y.
  const V3D toB = minus(cHat, t.b);
  const VD oneMinusZ = promote(u1) * setD(0.5) * dot(toB, toB);
  const VD z = one - oneMinusZ;
  const V3D side = minus(cHat, scaled(t.b, dot(cHat, t.b)));
  const VD sideLength = hn::Sqrt(dot(side, side));
  const V3D sideUnit{side.x / sideLength, side.y / sideLength, side.z / sideLength};
  const V3D w = normalized(plus(scaled(t.b, z), scaled(sideUnit, sqrtAtLeastZero(oneMinusZ * (one + z)))));
  return select(sideLength > hn::Zero(DD()), w, t.b);
}

// SphericalTriangle::pdfDirection of unit direction w where the map samples (1 / Ω inside the
// triangle, 0 outside), 0 in the other lanes.
HWY_INLINE VD pdfSphericalTriangle(const SphericalTriangleLanes& t, const V3D& w) {
  MD inside = t.inLanes;
  for (const V3D& m : t.edgeNormals) inside = hn::AndNot(dot(m, w) < setD(-1e-12), inside);
  return hn::IfThenElseZero(inside, setD(1.0) / t.solidAngle);
}

// SphericalRectangle::init (Ureña et al.'s map) of each lane's parallelogram light seen from x, as
// PolygonSolidAngle sets it up, in the lanes of m: inLanes where the map samples it (the rectangle's
// own map); scalar where SphericalRectangle samples it otherwise (a sheared parallelogram as two
// spherical triangles, a solid angle below SphericalRectangle::kMinSolidAngle by area); neither where
// it cannot be sampled.
struct SphericalRectangleLanes {
  V3D toCorner, eu, ev, normal, dualU, dualV, shear;
  VD z0, h, solidAngle, a0, a1, b0, b1, invA, invB, phi0, oneMinusCosDelta, onePlusCosSigma;
  MD swapped, unsheared;  // unsheared: shear == 0 exactly
  MD inLanes, scalar;
};

// oneMinusCos and onePlusCos (spherical_rectangle.cpp): 1 − cos and 1 + cos from cos c and sin s.
HWY_INLINE VD oneMinusCos(VD c, VD s) {
  const VD one = setD(1.0);
  return hn::IfThenElse(c > hn::Zero(DD()), s * s / (one + c), one - c);
}
HWY_INLINE VD onePlusCos(VD c, VD s) {
  const VD one = setD(1.0);
  return hn::IfThenElse(c < hn::Zero(DD()), s * s / (one - c), one + c);
}

HWY_INLINE SphericalRectangleLanes sphericalRectangle(const PolygonLanes& light, const V3F& x, MF m) {
  const DD dd;
  const VD zero = hn::Zero(dd), one = setD(1.0), infinity = setD(INFINITY);
  SphericalRectangleLanes r;
  const V3D xD = promote(x), corner = promote(light.p0);
  MD ok = validAndFacing(light, x, m);
  r.eu = promote(light.e1);
  r.ev = promote(light.e2);
  const V3D n = cross(r.eu, r.ev);
  const VD area = hn::Sqrt(dot(n, n));
  ok = hn::And(ok, hn::And(area > zero, area < infinity));
  r.normal = {n.x / area, n.y / area, n.z / area};
  r.toCorner = minus(corner, xD);
  const VD distance = hn::Sqrt(dot(r.toCorner, r.toCorner));
  r.z0 = dot(r.toCorner, r.normal);
  ok = hn::And(ok, hn::And(distance<infinity, hn::Abs(r.z0)> setD(1e-12) * distance));
  const V3D du = cross(r.ev, r.normal), dv = cross(r.normal, r.eu);
  r.dualU = {du.x / area, du.y / area, du.z / area};
  r.dualV = {dv.x / area, dv.y / area, dv.z / area};
  const VD lu = hn::Sqrt(dot(r.eu, r.eu)), lv = hn::Sqrt(dot(r.ev, r.ev));
  const MD sheared = hn::And(ok, hn::Abs(dot(r.eu, r.ev)) > setD(SphericalRectangle::kMaxEdgeCos) * lu * lv);
  ok = hn::AndNot(sheared, ok);
  // The rectangle's frame: x̂ along eu, ŷ the unit part of ev perpendicular to it.
  const V3D xHat{r.eu.x / lu, r.eu.y / lu, r.eu.z / lu};
  r.shear = scaled(xHat, dot(r.ev, xHat));
  r.unsheared = hn::And(hn::And(r.shear.x == zero, r.shear.y == zero), r.shear.z == zero);
  const V3D vPerp = minus(r.ev, r.shear);
  const VD height = hn::Sqrt(dot(vPerp, vPerp));
  const V3D yHat{vPerp.x / height, vPerp.y / height, vPerp.z / height};
  const VD h = hn::Abs(r.z0);
  r.h = h;
  const VD x0 = dot(r.toCorner, xHat), y0 = dot(r.toCorner, yHat);
  const VD x1 = x0 + lu, y1 = y0 + height;
  // Ω as the sum of the triangles v00 v10 v11 and v00 v11 v01 (Van Oosterom & Strackee).
  const VD h2 = h * h;
  const VD r00 = hn::Sqrt(x0 * x0 + y0 * y0 + h2), r10 = hn::Sqrt(x1 * x1 + y0 * y0 + h2),
           r11 = hn::Sqrt(x1 * x1 + y1 * y1 + h2), r01 = hn::Sqrt(x0 * x0 + y1 * y1 + h2);
  const VD diagonal = (x0 * x1 + y0 * y1 + h2) / (r00 * r11);
  const VD n1 = lu * height * h / (r00 * r10 * r11), n2 = lu * height * h / (r00 * r11 * r01);
  const VD d1 =
      one + (x0 * x1 + y0 * y0 + h2) / (r00 * r10) + (x1 * x1 + y0 * y1 + h2) / (r10 * r11) + diagonal;
  const VD d2 =
      one + diagonal + (x0 * x1 + y1 * y1 + h2) / (r11 * r01) + (x0 * x0 + y0 * y1 + h2) / (r01 * r00);
  const auto atan2Lanes = [](double y, double x) { return std::atan2(y, x); };
  r.solidAngle = setD(2.0) * libmLanes(ok, n1 * d2 + n2 * d1, d1 * d2 - n1 * n2, atan2Lanes);
  ok = hn::And(ok, hn::And(r.solidAngle > zero, r.solidAngle < infinity));
  const MD byArea = hn::And(ok, r.solidAngle < setD(SphericalRectangle::kMinSolidAngle));
  r.inLanes = hn::AndNot(byArea, ok);
  r.scalar = hn::Or(sheared, byArea);
  // The column runs along the axis whose extent across subtends the smaller angle.
  r.swapped = (h2 + x0 * x1) * (h * height) - (h * lu) * (h2 + y0 * y1) > zero;
  r.a0 = hn::IfThenElse(r.swapped, y0, x0);
  r.a1 = hn::IfThenElse(r.swapped, y1, x1);
  r.b0 = hn::IfThenElse(r.swapped, x0, y0);
  r.b1 = hn::IfThenElse(r.swapped, x1, y1);
  const VD a0 = r.a0, b0 = r.b0, b1 = r.b1;
  const VD lb = b1 - b0;
  r.invA = one / (r.a1 - a0);
  r.invB = one / lb;
  // φ₀ = Φ(a0).
  const VD s0 = hn::Sqrt(a0 * a0 + b0 * b0 + h2), s1 = hn::Sqrt(a0 * a0 + b1 * b1 + h2);
  const VD spread = hn::IfThenElse(b0 * b1 > zero, lb * (b1 + b0) * (a0 * a0 + h2) / (b1 * s0 + b0 * s1),
                                   b1 * s0 - b0 * s1);
  r.phi0 = libmLanes(r.inLanes, a0 * h * spread, h2 * s0 * s1 + a0 * a0 * b0 * b1, atan2Lanes);
  const VD rho = hn::Sqrt(h2 + b0 * b0) * hn::Sqrt(h2 + b1 * b1);
  r.oneMinusCosDelta = oneMinusCos((h2 + b0 * b1) / rho, h * lb / rho);
  r.onePlusCosSigma = onePlusCos((h2 - b0 * b1) / rho, h * (b0 + b1) / rho);
  return r;
}

// SphericalRectangle::sampleDirection through rectanglePoint, in the lanes of r.inLanes.
HWY_INLINE V3D sampleSphericalRectangle(const SphericalRectangleLanes& r, VF u0, VF u1) {
  const DD dd;
  const VD zero = hn::Zero(dd), one = setD(1.0), two = setD(2.0);
  const VD h = r.h, a0 = r.a0, a1 = r.a1, b0 = r.b0, b1 = r.b1;
  // u.x: the column A with Φ(A) = Φ(a0) + u.x Ω, in closed form.
  const VD phi = r.phi0 + promote(u0) * r.solidAngle;
  const VD half = setD(0.5) * phi;
  const VD sinHalf = libmLanes(r.inLanes, half, [](double v) { return std::sin(v); });
  const VD cosHalf = libmLanes(r.inLanes, half, [](double v) { return std::cos(v); });
  const VD twoS2 = two * sinHalf * sinHalf;
  const VD denominator = (r.oneMinusCosDelta - twoS2) * (r.onePlusCosSigma - twoS2);
  VD a = hn::IfThenElse(denominator > zero, two * h * sinHalf * cosHalf / hn::Sqrt(denominator),
                        hn::IfThenElse(phi > zero, a1, a0));
  a = clampD(a, a0, a1);
  // u.y: t(B) = B / √(d² + B²) linear in u.y from t(b0) to t(b1).
  const VD d2 = a * a + h * h, d = hn::Sqrt(d2);
  const VD rho0 = hn::Sqrt(d2 + b0 * b0), rho1 = hn::Sqrt(d2 + b1 * b1);
  const VD t0 = b0 / rho0, t1 = b1 / rho1;
  const VD c0 = d / rho0, c1 = d / rho1;
  const VD dt = hn::IfThenElse(b0 * b1 > zero,
                               (b1 - b0) * (b1 + b0) * d2 / ((b1 * rho0 + b0 * rho1) * rho0 * rho1), t1 - t0);
  const VD v = promote(u1), w = one - v;
  const VD delta = v * dt, t = t0 + delta;
  const VD oneMinus = w * hn::IfThenElse(t0 > zero, c0 * c0 / (one + t0), one - t0) +
                      v * hn::IfThenElse(t1 > zero, c1 * c1 / (one + t1), one - t1);
  const VD onePlus = w * hn::IfThenElse(t0 < zero, c0 * c0 / (one - t0), one + t0) +
                     v * hn::IfThenElse(t1 < zero, c1 * c1 / (one - t1), one + t1);
  const VD c = hn::Sqrt(oneMinus * onePlus);
  const VD rise = hn::IfThenElse(
      hn::Not(c > zero), hn::IfThenElse(t > zero, b1 - b0, zero),
      hn::IfThenElse(t * t0 > zero, d * delta * (t + t0) / ((t * c0 + t0 * c) * c * c0), t * d / c - b0));
  const VD sa = (a - a0) * r.invA, sb = clampD(rise * r.invB, zero, one);
  const VD s = hn::IfThenElse(r.swapped, sb, sa), tt = hn::IfThenElse(r.swapped, sa, sb);
  return normalized(plus(plus(r.toCorner, scaled(r.eu, s)), scaled(r.ev, tt)));
}

// SphericalRectangle::pdfDirection of unit direction w where the map samples (1 / Ω inside, times
// (d / d')³ for nearly perpendicular edges), 0 in the other lanes.
HWY_INLINE VD pdfSphericalRectangle(const SphericalRectangleLanes& r, const V3D& w) {
  const DD dd;
  const VD zero = hn::Zero(dd), one = setD(1.0);
  const VD cosLight = dot(r.normal, w);
  const VD t = r.z0 / cosLight;
  const V3D p = scaled(w, t);
  const V3D q = minus(p, r.toCorner);
  const VD s = dot(q, r.dualU), rr = dot(q, r.dualV);
  const VD lo = setD(-SphericalRectangle::kEdgeTolerance), hi = setD(1 + SphericalRectangle::kEdgeTolerance);
  const MD inside = hn::And(hn::And(hn::And(r.inLanes, cosLight != zero), t > zero),
                            hn::And(hn::And(s >= lo, s <= hi), hn::And(rr >= lo, rr <= hi)));
  const V3D unsheared = minus(p, scaled(r.shear, rr));
  const VD ratio = t / hn::Sqrt(dot(unsheared, unsheared));
  const VD density = hn::IfThenElse(r.unsheared, one / r.solidAngle, ratio * ratio * ratio / r.solidAngle);
  return hn::IfThenElseZero(inside, density);
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
