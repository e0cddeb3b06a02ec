#include "core/lights/spherical_rectangle.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

// 1 − cos and 1 + cos of an angle from its cos and sin, each without cancellation: the one that
// would cancel is sin² over the other.
double oneMinusCos(double c, double s) {
  return c > 0 ? s * s / (1 + c) : 1 - c;
}
double onePlusCos(double c, double s) {
  return c < 0 ? s * s / (1 - c) : 1 + c;
}

}  // namespace

bool SphericalRectangle::init(const Vec3& corner, const Vec3& edgeU, const Vec3& edgeV, const Vec3& x,
                              double minSolidAngle) {
  solidAngle = 0;
  byArea = false;
  sheared = false;
  eu = DVec3(edgeU);
  ev = DVec3(edgeV);
  const DVec3 n = glm::cross(eu, ev);
  area = glm::length(n);
  if (!(area > 0) || !std::isfinite(area)) return false;
  normal = n / area;
  toCorner = DVec3(corner) - DVec3(x);
  const double distance = glm::length(toCorner);
  z0 = glm::dot(toCorner, normal);
  if (!std::isfinite(distance) || !(std::fabs(z0) > 1e-12 * distance)) return false;  // x in its plane
  dualU = glm::cross(ev, normal) / area;
  dualV = glm::cross(normal, eu) / area;
  const double lu = glm::length(eu), lv = glm::length(ev);

  if (std::fabs(glm::dot(eu, ev)) > kMaxEdgeCos * lu * lv) {
    // A parallelogram: its two halves by Arvo's map, chosen by their solid angles; each half falls
    // back to area sampling below the triangle map's own threshold.
    sheared = true;
    const Vec3 c1 = corner + edgeU, c2 = c1 + edgeV, c3 = corner + edgeV;
    const double halfMin = std::max(minSolidAngle, SphericalTriangle::kMinSolidAngle);
    if (!halves[0].init(corner, c1, c2, x, halfMin) || !halves[1].init(corner, c2, c3, x, halfMin))
      return false;
    solidAngle = halves[0].solidAngle + halves[1].solidAngle;
    firstShare = halves[0].solidAngle / solidAngle;
    byArea = solidAngle < minSolidAngle;
    return true;
  }

  // The rectangle's frame: x̂ along eu, ŷ the unit part of ev perpendicular to it, x at the origin and
  // the rectangle [x0, x1] × [y0, y1] in the plane at distance h. The map samples the rectangle
  // spanned by eu and that part; its point (s, t) goes to corner + s eu + t ev, a shear by t shear.
  const DVec3 xHat = eu / lu;
  shear = glm::dot(ev, xHat) * xHat;
  const DVec3 vPerp = ev - shear;
  const double height = glm::length(vPerp);
  const DVec3 yHat = vPerp / height;
  h = std::fabs(z0);
  const double x0 = glm::dot(toCorner, xHat), y0 = glm::dot(toCorner, yHat);
  const double x1 = x0 + lu, y1 = y0 + height;

  // Ω as the sum of the triangles v00 v10 v11 and v00 v11 v01 (Van Oosterom & Strackee: tan(Ω/2) =
  // N / D), each N = lu · height · h / (|a| |b| |c|) without cancellation, added as one atan2 of the
  // product (D₁ + i N₁)(D₂ + i N₂).
  const double h2 = h * h;
  const double r00 = std::sqrt(x0 * x0 + y0 * y0 + h2), r10 = std::sqrt(x1 * x1 + y0 * y0 + h2),
               r11 = std::sqrt(x1 * x1 + y1 * y1 + h2), r01 = std::sqrt(x0 * x0 + y1 * y1 + h2);
  const double diagonal = (x0 * x1 + y0 * y1 + h2) / (r00 * r11);  // cos between v00 and v11
  const double n1 = lu * height * h / (r00 * r10 * r11), n2 = lu * height * h / (r00 * r11 * r01);
  const double d1 =
      1 + (x0 * x1 + y0 * y0 + h2) / (r00 * r10) + (x1 * x1 + y0 * y1 + h2) / (r10 * r11) + diagonal;
  const double d2 =
      1 + diagonal + (x0 * x1 + y1 * y1 + h2) / (r11 * r01) + (x0 * x0 + y0 * y1 + h2) / (r01 * r00);
  solidAngle = 2 * std::atan2(n1 * d2 + n2 * d1, d1 * d2 - n1 * n2);
  if (!(solidAngle > 0) || !std::isfinite(solidAngle)) {
    solidAngle = 0;
    return false;
  }
  if (solidAngle < minSolidAngle) {
    byArea = true;
    return true;
  }

  // The map measures the column's solid angle from the foot of x, up to Δ: its error is about an
  // ulp of Δ, so the column runs along the axis whose extent across subtends the smaller Δ
  // (tan Δ_y = h height / (h² + y0 y1), tan Δ_x = h lu / (h² + x0 x1); both in (0, π)).
  swapped = (h2 + x0 * x1) * (h * height) - (h * lu) * (h2 + y0 * y1) > 0;  // Δ_x < Δ_y
  if (swapped) {
    a0 = y0, a1 = y1, b0 = x0, b1 = x1;
  } else {
    a0 = x0, a1 = x1, b0 = y0, b1 = y1;
  }
  const double lb = b1 - b0;
  invA = 1 / (a1 - a0);
  invB = 1 / lb;
  // φ₀ = Φ(a0), the solid angle of [0, a0] × [b0, b1]: arg((h r01 + i a0 b1) conj(h r00 + i a0 b0))
  // with r0j = |(a0, b_j, h)|. Its imaginary part a0 h (b1 r00 − b0 r01) is formed without
  // cancellation when b0, b1 share a sign.
  const double s0 = std::sqrt(a0 * a0 + b0 * b0 + h2), s1 = std::sqrt(a0 * a0 + b1 * b1 + h2);
  const double spread =
      b0 * b1 > 0 ? lb * (b1 + b0) * (a0 * a0 + h2) / (b1 * s0 + b0 * s1) : b1 * s0 - b0 * s1;
  phi0 = std::atan2(a0 * h * spread, h2 * s0 * s1 + a0 * a0 * b0 * b1);
  // θ_j = atan(b_j / h), Δ = θ1 − θ0, σ = θ0 + θ1, by their cos and sin.
  const double rho = std::sqrt(h2 + b0 * b0) * std::sqrt(h2 + b1 * b1);
  oneMinusCosDelta = oneMinusCos((h2 + b0 * b1) / rho, h * lb / rho);
  onePlusCosSigma = onePlusCos((h2 - b0 * b1) / rho, h * (b0 + b1) / rho);
  return true;
}

DVec3 SphericalRectangle::sampleDirection(Vec2 u) const {
  if (byArea) return glm::normalize(toCorner + eu * double(u.x) + ev * double(u.y));
  if (sheared) {
    const double ux = double(u.x);
    const int i = ux < firstShare ? 0 : 1;
    const double rescaled = i == 0 ? ux / firstShare : (ux - firstShare) / (1 - firstShare);
    return halves[i].sampleDirection(Vec2(std::min(float(rescaled), kOneMinusEpsilon), u.y));
  }
  const glm::dvec2 st = rectanglePoint(u);
  return glm::normalize(toCorner + st.x * eu + st.y * ev);
}

glm::dvec2 SphericalRectangle::rectanglePoint(Vec2 u) const {
  // u.x: the column A with Φ(A) = φ = Φ(a0) + u.x Ω, in closed form
  //   A = h sin φ / √((cos φ − cos Δ)(cos φ + cos σ)),
  // with cos φ − cos Δ = (1 − cos Δ) − 2 sin²(φ/2) and cos φ + cos σ = (1 + cos σ) − 2 sin²(φ/2).
  const double phi = phi0 + double(u.x) * solidAngle;
  const double sinHalf = std::sin(0.5 * phi), cosHalf = std::cos(0.5 * phi);
  const double twoS2 = 2 * sinHalf * sinHalf;
  const double denominator = (oneMinusCosDelta - twoS2) * (onePlusCosSigma - twoS2);
  double a = denominator > 0 ? 2 * h * sinHalf * cosHalf / std::sqrt(denominator) : (phi > 0 ? a1 : a0);
  a = std::clamp(a, a0, a1);
  // u.y: along the column the solid angle below B is proportional to t(B) = B / √(d² + B²) (d² = A² +
  // h²), linear in u.y from t0 = t(b0) to t1 = t(b1). t1 − t0 and B − b0 are formed from differences
  // of squares (no cancellation when b0, b1 share a sign), 1 − t² from 1 − t and 1 + t, each a
  // convex combination of its endpoint values formed without cancellation.
  const double d2 = a * a + h * h, d = std::sqrt(d2);
  const double rho0 = std::sqrt(d2 + b0 * b0), rho1 = std::sqrt(d2 + b1 * b1);
  const double t0 = b0 / rho0, t1 = b1 / rho1;
  const double c0 = d / rho0, c1 = d / rho1;  // √(1 − t_j²)
  const double dt =
      b0 * b1 > 0 ? (b1 - b0) * (b1 + b0) * d2 / ((b1 * rho0 + b0 * rho1) * rho0 * rho1) : t1 - t0;
  const double v = double(u.y), w = 1 - v;
  const double delta = v * dt, t = t0 + delta;
  const double oneMinus =
      w * (t0 > 0 ? c0 * c0 / (1 + t0) : 1 - t0) + v * (t1 > 0 ? c1 * c1 / (1 + t1) : 1 - t1);
  const double onePlus =
      w * (t0 < 0 ? c0 * c0 / (1 - t0) : 1 + t0) + v * (t1 < 0 ? c1 * c1 / (1 - t1) : 1 + t1);
  const double c = std::sqrt(oneMinus * onePlus);
  // B − b0 = d (t / c − t0 / c0) = d (t² − t0²) / ((t c0 + t0 c) c c0).
  double rise;
  if (!(c > 0))
    rise = t > 0 ? b1 - b0 : 0;
  else if (t * t0 > 0)
    rise = d * delta * (t + t0) / ((t * c0 + t0 * c) * c * c0);
  else
    rise = t * d / c - b0;
  const double sa = (a - a0) * invA, sb = std::clamp(rise * invB, 0.0, 1.0);
  return swapped ? glm::dvec2(sb, sa) : glm::dvec2(sa, sb);
}

double SphericalRectangle::pdfDirection(const DVec3& w) const {
  if (!(solidAngle > 0)) return 0;
  if (sheared && !byArea) {
    const double first = halves[0].pdfDirection(w);
    return first > 0 ? firstShare * first : (1 - firstShare) * halves[1].pdfDirection(w);
  }
  const double cosLight = glm::dot(normal, w);
  if (cosLight == 0) return 0;
  const double t = z0 / cosLight;
  if (!(t > 0)) return 0;
  const DVec3 p = w * t;
  const DVec3 q = p - toCorner;
  const double s = glm::dot(q, dualU), r = glm::dot(q, dualV);
  if (!(s >= -kEdgeTolerance && s <= 1 + kEdgeTolerance && r >= -kEdgeTolerance && r <= 1 + kEdgeTolerance))
    return 0;
  if (byArea) return t * t / (area * std::fabs(cosLight));
  if (shear == DVec3(0)) return 1 / solidAngle;
  // The shear keeps area: the density per area at p is the rectangle's at p − r shear, h / (d'³ Ω),
  // so per solid angle (d / d')³ / Ω.
  const double ratio = t / glm::length(p - r * shear);
  return ratio * ratio * ratio / solidAngle;
}

}  // namespace penumbra
