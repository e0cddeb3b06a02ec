#include "core/lights/projected_cap.h"

#include <algorithm>
#include <cmath>

#include "core/lights/sphere_cap.h"
#include "core/math/frame.h"
#include "core/math/vec.h"
#include "core/sampling/warp.h"

namespace penumbra {
namespace {

// Below this Ω⊥ the pdf cos θ / Ω⊥ could exceed float's range.
constexpr double kMinProjectedSolidAngle = 0x1p-120;
// Float directions carry ~2^-24 relative error per component (see SphereLight::pdfSolidAngle).
constexpr double kDirectionSlack = 0x1p-22;
constexpr double kQuarterPi = 0.78539816339744830962;

double sqrtNonNeg(double v) {
  return std::sqrt(std::max(v, 0.0));
}

// G(u) = ∫₀ᵘ √(1 − t²) dt = (u √(1 − u²) + asin u) / 2, given s = √(1 − u²).
double quarterDiskArea(double u, double s) {
  return 0.5 * (u * s + std::asin(u));
}

// H(y) = ∫₀ʸ t² / √(1 − t²) dt = (asin y − y √(1 − y²)) / 2 = G(y) − y √(1 − y²), given s = √(1 − y²):
// the part of the unit circle's quarter area beyond the slice widths measured from x = √(1 − y²).
// O(y³): by its series Σ c_k y^{2k+3} / (2k+3), c_k = (2k choose k) / 4^k, below y = 1/4, where the
// closed form would cancel (a small cap straddling the horizon has y ~ sin α).
double circleExcessArea(double y, double s) {
  if (y >= 0.25) return 0.5 * (std::asin(y) - y * s);
  const double y2 = y * y;
  double power = y * y2, c = 1.0, sum = 0.0;
  for (int k = 0; k < 24; ++k) {
    const double term = c * power / (2 * k + 3);
    sum += term;
    if (term <= 1e-17 * sum) break;
    c *= (2.0 * k + 1.0) / (2.0 * k + 2.0);
    power *= y2;
  }
  return sum;
}

}  // namespace

// √(1 − y²) − xc as (k − y²) / (√(1 − y²) + xc) (no cancellation for small caps); 0 where both vanish
// (x on the light's surface at y = 1).
double ProjectedSphereCap::circleGap(double y, double s1) const {
  const double sum = s1 + xc;
  return sum > 0.0 ? (k - y * y) / sum : 0.0;
}

bool ProjectedSphereCap::init(const SphereLight& light, const Vec3& x, const Vec3& n) {
  const double r = light.sphere.radius;
  origin = DVec3(x);
  toCenter = DVec3(light.sphere.center) - origin;  // exact: float inputs
  const double d2 = glm::dot(toCenter, toCenter);
  const double d = std::sqrt(d2);
  if (!(r > 0.0) || !(d >= r) || !std::isfinite(d)) return false;
  radius = r;
  distance = d;
  radiance = light.radiance;

  ez = DVec3(n);  // unit to float precision: the frame's and Ω⊥'s error stays at float rounding
  const double invD = 1.0 / d;
  const DVec3 wc = toCenter * invD;
  sinAlpha = r * invD;
  cosAlpha = std::sqrt((d - r) * (d + r)) * invD;
  cosCentre = glm::dot(wc, ez);
  if (cosCentre <= -sinAlpha) return false;  // entirely below the horizon
  // sin θ and the frame from the cross product: accurate near θ = 0 and for narrow caps.
  const DVec3 side = glm::cross(ez, wc);
  sinCentre = std::sqrt(glm::dot(side, side));
  if (sinCentre > 0.0) {
    ey = side * (1.0 / sinCentre);
    ex = glm::cross(ey, ez);  // = (wc − cos θ ez) / sin θ
  } else {
    orthonormalBasis(ez, ex, ey);
  }

  xc = cosAlpha * sinCentre;
  a = sinAlpha * cosCentre;
  b = sinAlpha;
  k = sinAlpha * sinAlpha + cosAlpha * cosAlpha * cosCentre * cosCentre;
  straddling = cosCentre < sinAlpha;
  // The closed form; above the horizon it is the ellipse's area π a b (its first case, inlined).
  projectedSolidAngle =
      straddling ? sphereLightIrradianceFactor(cosCentre, sinCentre, sinAlpha, cosAlpha) : kPiD * a * b;
  if (!(projectedSolidAngle >= kMinProjectedSolidAngle)) return false;
  invProjectedSolidAngle = 1.0 / projectedSolidAngle;
  if (straddling) {
    // Tangent points: x = cos α / sin θ on the unit circle, y² = 1 − x² = (sin²α − cos²θ) / sin²θ.
    const double yt =
        sinCentre > 0.0 ? sqrtNonNeg((sinAlpha - cosCentre) * (sinAlpha + cosCentre)) / sinCentre : b;
    yTangent = std::min(yt, b);
    yMax = a > 0.0 ? b : yTangent;
    const double u = yTangent / b;
    gTangent = quarterDiskArea(u, sqrtNonNeg((1.0 - u) * (1.0 + u)));
    areaBelowTangent = areaBelow(yTangent);
    // Centre above the horizon: the ellipse's part with |y| > yTangent lies inside the disk.
    halfArea = a > 0.0 ? areaBelowTangent + 2.0 * a * b * (kQuarterPi - gTangent) : areaBelowTangent;
    inversionTolerance = std::max(kAreaTolerance * halfArea, 8 * 0x1p-52 * yMax * (k + std::fabs(a) * b));
    // The inversion's first guess: the area left above y behaves like c (yMax − y)^p near yMax (p = 3/2
    // at an ellipse's top, 2 at a circle's chord, 3 where the ellipse touches the circle); fit c and p
    // from two heights near the end.
    const double r1 = halfArea - areaBelow(0.9 * yMax), r2 = halfArea - areaBelow(0.99 * yMax);
    endPower = (r1 > 0.0 && r2 > 0.0) ? std::clamp(std::log(r1 / r2) / std::log(10.0), 1.0, 4.0) : 1.5;
    endScale = r1 > 0.0 ? r1 / std::pow(0.1 * yMax, endPower) : 0.0;
    startWidth = sliceWidth(0.0);
  }
  return true;
}

// Slices of the straddling region at height y ≥ 0, in x = xc + δx (δx measured from the ellipse centre):
//   |y| ≤ yTangent:  δx from −a √(1 − y²/b²) (the ellipse's arc above the horizon: its inner arc for
//                    a > 0, its outer one for a < 0) to √(1 − y²) − xc (the unit circle);
//   |y| > yTangent:  (a > 0 only) the ellipse's chord, δx ∈ ±a √(1 − y²/b²).
// √(1 − y²) − xc is evaluated as (k − y²) / (√(1 − y²) + xc), so no width cancels for small caps.
double ProjectedSphereCap::sliceWidth(double y) const {
  const double s1 = sqrtNonNeg((1.0 - y) * (1.0 + y));
  const double u = std::min(1.0, y / b);
  const double s2 = sqrtNonNeg((1.0 - u) * (1.0 + u));
  if (y <= yTangent) return std::max(0.0, circleGap(y, s1) + a * s2);
  return 2.0 * a * s2;
}

// ∫₀ʸ sliceWidth: with ∫₀ʸ (√(1 − t²) − xc) dt = H(y) + y (√(1 − t²) − xc) and ∫₀ʸ √(1 − t²/b²) dt
// = b G(y/b), the area below the tangent height is H(y) + y (k − y²)/(√(1 − y²) + xc) + a b G(y/b).
double ProjectedSphereCap::areaBelow(double y) const {
  const double u = std::min(1.0, y / b);
  const double s2 = sqrtNonNeg((1.0 - u) * (1.0 + u));
  if (y > yTangent) return areaBelowTangent + 2.0 * a * b * (quarterDiskArea(u, s2) - gTangent);
  const double s1 = sqrtNonNeg((1.0 - y) * (1.0 + y));
  return circleExcessArea(y, s1) + y * circleGap(y, s1) + a * b * quarterDiskArea(u, s2);
}

// Newton's method on the monotone areaBelow, kept inside a shrinking bracket: a step that leaves it
// (flat slices near yMax, where the width vanishes) is replaced by bisection.
ProjectedSphereCap::Inversion ProjectedSphereCap::invertArea(double target) const {
  if (!(target > 0.0)) return {0.0, 0};
  if (!(target < halfArea)) return {yMax, 0};
  double lo = 0.0, hi = yMax;
  // Below the linear guess, since the area is concave (slices narrow with |y|); the end's power law
  // where that is further up.
  double y = target / startWidth;
  if (endScale > 0.0) y = std::max(y, yMax - std::pow((halfArea - target) / endScale, 1.0 / endPower));
  if (!(y > lo && y < hi)) y = 0.5 * (lo + hi);
  const double ulps = 4 * 0x1p-52 * yMax;
  int step = 0;
  while (step < kMaxInversionSteps) {
    ++step;
    // areaBelow(y) and sliceWidth(y), sharing their square roots.
    const double s1 = sqrtNonNeg((1.0 - y) * (1.0 + y));
    const double u = std::min(1.0, y / b);
    const double s2 = sqrtNonNeg((1.0 - u) * (1.0 + u));
    double area, width;
    if (y > yTangent) {
      area = areaBelowTangent + 2.0 * a * b * (quarterDiskArea(u, s2) - gTangent);
      width = 2.0 * a * s2;
    } else {
      const double circle = circleGap(y, s1);
      area = circleExcessArea(y, s1) + y * circle + a * b * quarterDiskArea(u, s2);
      width = std::max(0.0, circle + a * s2);
    }
    const double f = area - target;
    if (std::fabs(f) <= inversionTolerance) break;
    (f < 0.0 ? lo : hi) = y;
    double next = y - f / width;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::fabs(next - y) <= ulps || hi - lo <= ulps) break;
    y = next;
  }
  return {y, step};
}

ProjectedSphereCap::Direction ProjectedSphereCap::sampleDirection(Vec2 u) const {
  double dx, y;
  if (!straddling) {
    // Peters & Dachsbacher (I3D 2019): the unclipped ellipse is an affine image of the disk.
    const Vec2 disk = Warp::squareToConcentricDisk(u);
    dx = a * double(disk.x);
    y = b * double(disk.y);
  } else {
    // Ureña & Georgiev (EGSR 2018), parallel map: y from the inverted marginal area, x on its slice.
    const double v = 2.0 * double(u.x) - 1.0;
    const double yAbs = invertArea(std::fabs(v) * halfArea).y;
    const double t = std::min(1.0, yAbs / b);
    dx = -a * sqrtNonNeg((1.0 - t) * (1.0 + t)) + double(u.y) * sliceWidth(yAbs);
    y = std::copysign(yAbs, v);
  }
  // Nusselt: lift (xc + δx, y) onto the hemisphere, z² = 1 − (xc + δx)² − y².
  const double z = sqrtNonNeg(k - y * y - dx * (2.0 * xc + dx));
  return {(xc + dx) * ex + y * ey + z * ez, z};
}

LightSample ProjectedSphereCap::sample(Vec2 u) const {
  const Direction dir = sampleDirection(u);
  // The near intersection with the sphere: t = (d² − r²) / (t_ca + √(r² − |c − x − t_ca w|²)) (no
  // cancellation for x next to the light).
  const double tca = glm::dot(dir.w, toCenter);
  const DVec3 perp = toCenter - tca * dir.w;
  const double h = sqrtNonNeg(radius * radius - glm::dot(perp, perp));
  const double dist = (glm::dot(toCenter, toCenter) - radius * radius) / (tca + h);
  const Vec3 fromCenter(dist * dir.w - toCenter);
  LightSample ls;
  ls.wi = Vec3(dir.w);
  ls.dist = static_cast<float>(dist);
  ls.p = Vec3(origin + dist * dir.w);
  ls.n = fromCenter * (1.f / static_cast<float>(radius));
  ls.pdf = static_cast<float>(dir.cosTheta * invProjectedSolidAngle);
  ls.Le = radiance;
  return ls;
}

double ProjectedSphereCap::pdfDirection(const DVec3& w) const {
  const double len2 = glm::dot(w, w);
  if (!(len2 > 0.0) || glm::dot(w, toCenter) <= 0.0) return 0.0;
  const DVec3 c = glm::cross(w, toCenter);
  if (glm::dot(c, c) > sinAlpha * sinAlpha * len2 * distance * distance) return 0.0;
  const double cosTheta = glm::dot(w, ez) / std::sqrt(len2);
  return cosTheta > 0.0 ? cosTheta * invProjectedSolidAngle : 0.0;
}

float ProjectedSphereCap::pdf(const Vec3& wf) const {
  const DVec3 w(wf);
  const double len2 = glm::dot(w, w);
  if (!(len2 > 0.0) || glm::dot(w, toCenter) <= 0.0) return 0.f;
  const DVec3 c = glm::cross(w, toCenter);
  const double sinMax = sinAlpha + kDirectionSlack;
  if (glm::dot(c, c) > sinMax * sinMax * len2 * distance * distance) return 0.f;
  const double cosTheta = glm::dot(w, ez) / std::sqrt(len2);
  return cosTheta > 0.0 ? static_cast<float>(cosTheta * invProjectedSolidAngle) : 0.f;
}

}  // namespace penumbra
