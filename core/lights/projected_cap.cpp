#include "core/lights/projected_cap.h"

#include <algorithm>
#include <cmath>

#include "core/lights/sphere_cap.h"
#include "core/math/circular_segment.h"
#include "core/math/frame.h"
#include "core/math/vec.h"
#include "core/sampling/warp.h"

namespace penumbra {
namespace {

constexpr double kMinProjectedSolidAngle = ProjectedSphereCap::kMinProjectedSolidAngle;
constexpr double kDirectionSlack = ProjectedSphereCap::kDirectionSlack;

double sqrtNonNeg(double v) {
  return std::sqrt(std::max(v, 0.0));
}

// Below this y, H(y) by a polynomial (closed form above: it cancels to 3ε/y² ≤ 5e-15 of H there).
constexpr double kCircleSeriesLimit = 0.25;

// H(y) = ∫₀ʸ t² / √(1 − t²) dt = (asin y − y √(1 − y²)) / 2 = G(y) − y √(1 − y²), given s = √(1 − y²):
// the part of the unit circle's quarter area beyond the slice widths measured from x = √(1 − y²).
// O(y³): below y = 1/4, where the closed form would cancel (a small cap straddling the horizon has
// y ~ sin α), H(y) / y³ by its Chebyshev fit of degree 8 in y² (relative error 4e-18 on [0, 1/16] in
// y², fitted to the series Σ c_k y^{2k} / (2k+3), c_k = (2k choose k) / 4^k, in 40 digits), by
// Estrin's scheme (no divisions, a short dependency chain).
double circleExcessArea(double y, double s) {
  if (y >= kCircleSeriesLimit) return 0.5 * (std::asin(y) - y * s);
  const double z = y * y, z2 = z * z, z4 = z2 * z2;
  const double p01 = 0.333333333333333334592 + z * 0.0999999999999967391912;
  const double p23 = 0.053571428572817479881 + z * 0.0347222219948132468751;
  const double p45 = 0.0248579731595492062207 + z * 0.0189294351253255839617;
  const double p67 = 0.0150619292492544180941 + z * 0.0119682154926360764567;
  const double p8 = 0.0132162705503589562782;
  return y * z * ((p01 + z2 * p23) + z4 * ((p45 + z2 * p67) + z4 * p8));
}

// asin s given c = √(1 − s²) (s, c ≥ 0) through the smaller leg: asin s = 2 H(s) + s c, or π/2 minus
// that of c, so H's polynomial serves where the smaller leg is below 1/4, and an arcsine of at most
// 1/√2 (well conditioned) elsewhere.
double arcsine(double s, double c) {
  return s <= c ? 2.0 * circleExcessArea(s, c) + s * c : 0.5 * kPiD - (2.0 * circleExcessArea(c, s) + s * c);
}

// G(u) = ∫₀ᵘ √(1 − t²) dt = (u √(1 − u²) + asin u) / 2, given s = √(1 − u²).
double quarterDiskArea(double u, double s) {
  return 0.5 * (u * s + arcsine(u, s));
}

// sin and cos of |δ| ≤ 1/8 by their Taylor polynomials (truncated below 2^-55 of the value).
SinCosD sinCosSmall(double d) {
  const double d2 = d * d;
  const double s =
      d * (1.0 + d2 * (-1.0 / 6.0 + d2 * (1.0 / 120.0 + d2 * (-1.0 / 5040.0 + d2 * (1.0 / 362880.0)))));
  const double c =
      1.0 +
      d2 * (-0.5 + d2 * (1.0 / 24.0 + d2 * (-1.0 / 720.0 + d2 * (1.0 / 40320.0 + d2 * (-1.0 / 3628800.0)))));
  return {s, c};
}

}  // namespace

// √(1 − y²) − xc as (k − y²) / (√(1 − y²) + xc) (no cancellation for small caps); 0 where both vanish
// (x on the light's surface at y = 1).
double ProjectedSphereCap::circleGap(double y, double s1) const {
  const double sum = s1 + xc;
  return sum > 0.0 ? (k - y * y) / sum : 0.0;
}

bool ProjectedSphereCap::init(const SphereLight& light, const Vec3& x, const Vec3& n) {
  // What a caller may read after a false return: nothing to sample, Ω⊥ = 0.
  projectedSolidAngle = invProjectedSolidAngle = 0.0;
  map = Map::Ellipse;
  straddling = false;
  const double r = light.sphere.radius;
  origin = DVec3(x);
  toCenter = DVec3(light.sphere.center) - origin;  // exact: float inputs
  ez = DVec3(n);  // unit to float precision: the frame's and Ω⊥'s error stays at float rounding
  // The three square roots and then the two divisions do not wait for each other (this runs once per
  // sample when an integrator takes one light sample per shading point). sin θ and the frame come from
  // the cross product (accurate near θ = 0 and for narrow caps); d² − r² is as accurate as (d − r)(d + r)
  // (d² is exact to one rounding, r² exact).
  const DVec3 side = glm::cross(ez, toCenter);  // |side| = d sin θ
  const double d2 = glm::dot(toCenter, toCenter), side2 = glm::dot(side, side);
  const double d = std::sqrt(d2), sideLength = std::sqrt(side2), tangentLength = sqrtNonNeg(d2 - r * r);
  if (!(r > 0.0) || !(d >= r) || !std::isfinite(d)) return false;
  radius = r;
  distance = d;
  radiance = light.radiance;
  const double invD = 1.0 / d;
  sinAlpha = r * invD;
  cosAlpha = tangentLength * invD;
  cosCentre = glm::dot(toCenter, ez) * invD;
  if (cosCentre <= -sinAlpha) return false;  // entirely below the horizon
  sinCentre = sideLength * invD;
  const double invSideLength = 1.0 / sideLength;  // 1 / (d sin θ)
  if (sideLength > 0.0) {
    ey = side * invSideLength;
    ex = glm::cross(ey, ez);  // = (wc − cos θ ez) / sin θ
  } else {
    orthonormalBasis(ez, ex, ey);
  }

  xc = cosAlpha * sinCentre;
  a = sinAlpha * cosCentre;
  b = sinAlpha;
  k = sinAlpha * sinAlpha + cosAlpha * cosAlpha * cosCentre * cosCentre;
  straddling = cosCentre < sinAlpha;
  if (!straddling) {
    // The ellipse's area π a b: the closed form's first case.
    projectedSolidAngle = kPiD * a * b;
  } else {
    invB = d / r;
    // Tangent points: x = cos α / sin θ on the unit circle, y² = 1 − x² = (sin²α − cos²θ) / sin²θ.
    const double yt =
        sinCentre > 0.0 ? sqrtNonNeg((sinAlpha - cosCentre) * (sinAlpha + cosCentre)) * d * invSideLength : b;
    yTangent = std::min(yt, b);
    if (a >= 0.0)
      initCutDisks(d * invSideLength);
    else
      initLens();
  }
  if (!(projectedSolidAngle >= kMinProjectedSolidAngle)) return false;
  invProjectedSolidAngle = 1.0 / projectedSolidAngle;
  return true;
}

// Straddling with the centre on or above the horizon: the ellipse's part left of the tangent points'
// x (a disk cut by a chord, in the ellipse's own unit disk: X = (x − xc) / a = −cos β, Y = y / b =
// sin β at βt) and the unit disk's segment right of it (x = cos γ, y = sin γ at γt).
void ProjectedSphereCap::initCutDisks(double invSinCentre) {
  map = Map::CutDisks;
  const double yt = yTangent, xt = std::min(1.0, cosAlpha * invSinCentre);
  // The pieces' areas g(γt) and a b g(βt), each through its smaller leg, so that an arcsine's argument
  // is at most 1/√2 (well conditioned): g(γ) = 2 H(sin γ) for γ ≤ π/4 (H = circleExcessArea, a
  // polynomial below sin γ = 1/4 and the arcsine above), γ = π/2 − asin(cos γ) beyond.
  const double circlePiece =
      yt <= xt ? 2.0 * circleExcessArea(yt, xt) : segmentArea(arcsine(yt, xt), SinCosD{yt, xt});
  // X_t = (xt − xc) / a = cot θ cot α (no cancellation), Y_t = yt / b; βt ∈ [π/2, π), cos βt = −X_t:
  // g(βt) = π − g(π − βt) = π − 2 H(Y_t), or with βt = π/2 + asin X_t, asin X_t = 2 H(X_t) + X_t Y_t,
  // g(βt) = π/2 + 2 H(X_t) + 2 X_t Y_t.
  const double bigX = std::min(1.0, cosAlpha * cosCentre * invB * invSinCentre);
  const double bigY = std::min(1.0, yt * invB);
  const double ellipseG = bigY <= bigX ? kPiD - 2.0 * circleExcessArea(bigY, bigX)
                                       : 0.5 * kPiD + 2.0 * (circleExcessArea(bigX, bigY) + bigX * bigY);
  invAB = 1.0 / (a * b);
  ellipsePieceArea = a * b * ellipseG;
  projectedSolidAngle = ellipsePieceArea + circlePiece;
}

// Straddling with the centre below the horizon: the lens between the ellipse's outer arc and the
// circle, mapped by slices of constant y (see invertArea).
void ProjectedSphereCap::initLens() {
  map = Map::Lens;
  yMax = yTangent;
  const double u = std::min(1.0, yTangent * invB);
  const double s1 = sqrtNonNeg((1.0 - yTangent) * (1.0 + yTangent));
  // The inversion runs in the ellipse's angle φ, y = b sin φ, up to the tangent.
  cosPhiTangent = sqrtNonNeg((1.0 - u) * (1.0 + u));
  phiTangent = arcsine(u, cosPhiTangent);
  phiMax = phiTangent;
  gTangent = 0.5 * (u * cosPhiTangent + phiTangent);
  areaBelowTangent = circleExcessArea(yTangent, s1) + yTangent * circleGap(yTangent, s1) + a * b * gTangent;
  halfArea = areaBelowTangent;
  // Ω⊥ is the area the map covers, so the pdf is the density it samples; it equals the closed form of
  // sphere_cap.h to rounding (ProjectedSphereCap.MappedAreaEqualsTheClosedForm).
  projectedSolidAngle = 2.0 * halfArea;
  // M₃ ≥ |A'''| on [0, phiMax] (y = b sin φ, A = C(y) + E(φ), C(y) = ∫₀ʸ g, g(t) = √(1 − t²) − xc ∈
  // [0, 1 − xc] below the tangent, E = a b (φ + sin φ cos φ) / 2): |E'''| ≤ 2|a|b and, by the chain
  // rule (C''' = g'' y'³ + 3 g' y' y'' + g y''', |y' y''| ≤ b²/2) with |g'| ≤ Y/s₁, |g''| ≤ 1/s₁³ for
  // y ≤ Y = yTangent ≤ b (s₁ = √(1 − Y²) ≤ 1), |C'''| ≤ b³/s₁³ + 1.5 b²Y/s₁ + b(1 − xc) ≤
  // b (2.5 b²/s₁³ + 1 − xc).
  areaThirdDerivativeBound =
      b * (2.0 * std::fabs(a) + (1.0 - xc) + 2.5 * b * b / std::max(s1 * s1 * s1, 1e-290));
  inversionTolerance = std::max(kAreaTolerance * halfArea, 32 * 0x1p-52 * yMax * (k + std::fabs(a) * b));
  // The inversion's first guess inverts A(y) ≈ w₀ y − g y³ (A is odd in y: the slices are even), g
  // from A(yMax) = halfArea, kept where the model stays increasing on [0, yMax].
  startWidth = std::max(0.0, k / (1.0 + xc) + a);  // sliceWidth(0)
  invStartWidth = 1.0 / startWidth;
  const double invYMax3 = 1.0 / (yMax * yMax * yMax);
  startCubic = std::clamp((startWidth * yMax - halfArea) * invYMax3, 0.0, startWidth * yMax * invYMax3 / 3.0);
}

// Slices of the lens at height 0 ≤ y ≤ yTangent, in x = xc + δx (δx measured from the ellipse centre):
// δx from −a √(1 − y²/b²) (the ellipse's outer arc, a < 0) to √(1 − y²) − xc (the unit circle).
// √(1 − y²) − xc is evaluated as (k − y²) / (√(1 − y²) + xc), so no width cancels for small caps.
// The area below y, ∫₀ʸ width: with ∫₀ʸ (√(1 − t²) − xc) dt = H(y) + y (√(1 − y²) − xc) and
// ∫₀ʸ √(1 − t²/b²) dt = b G(y/b), it is H(y) + y (k − y²)/(√(1 − y²) + xc) + a b G(y/b). slope: d width / dy
// (for the inversion's stop rule), −y/√(1 − y²) − a (y/b²)/√(1 − y²/b²).
ProjectedSphereCap::Slice ProjectedSphereCap::slice(double y) const {
  const double u = std::min(1.0, y * invB);
  const double s2 = sqrtNonNeg((1.0 - u) * (1.0 + u));
  const double s1 = sqrtNonNeg((1.0 - y) * (1.0 + y));
  const double circle = circleGap(y, s1);
  return {circleExcessArea(y, s1) + y * circle + a * b * quarterDiskArea(u, s2),
          std::max(0.0, circle + a * s2), -y / std::max(s1, 0x1p-1000) - a * u / std::max(b * s2, 0x1p-1000)};
}

double ProjectedSphereCap::sliceWidth(double y) const {
  const double u = std::min(1.0, y * invB);
  const double s2 = sqrtNonNeg((1.0 - u) * (1.0 + u));
  return std::max(0.0, circleGap(y, sqrtNonNeg((1.0 - y) * (1.0 + y))) + a * s2);
}

double ProjectedSphereCap::areaBelow(double y) const {
  return slice(y).area;
}

// The area below y = b sin φ and its first two derivatives in φ, from sin φ and cos φ (no inverse
// trigonometry: the ellipse's part a b G(sin φ) is a b (φ + sin φ cos φ) / 2). With w the slice width,
// dA/dφ = w b cos φ and d²A/dφ² = b (cos φ dw/dφ − sin φ w), dw/dφ = −b cos φ y / √(1 − y²) − a sin φ.
// Inlined into the inversion loop (the compiler would otherwise call it there).
[[gnu::always_inline]] inline ProjectedSphereCap::ArcSlice ProjectedSphereCap::arcSlice(double phi,
                                                                                        double sinPhi,
                                                                                        double cosPhi) const {
  const double y = b * sinPhi;
  const double ellipse = 0.5 * a * b * (phi + sinPhi * cosPhi);
  const double s1 = sqrtNonNeg((1.0 - y) * (1.0 + y));
  // One division for both 1 / (√(1 − y²) + xc) (the circle's gap, as in circleGap) and 1 / √(1 − y²).
  const double sum = s1 + xc;
  const double inv = 1.0 / std::max(s1 * sum, 0x1p-1000);
  const double circle = sum > 0.0 ? (k - y * y) * s1 * inv : 0.0;
  const double w = std::max(0.0, circle + a * cosPhi);
  const double dw = -b * cosPhi * y * sum * inv - a * sinPhi;
  return {circleExcessArea(y, s1) + y * circle + ellipse, w * b * cosPhi, b * (cosPhi * dw - sinPhi * w)};
}

// Halley's method on the monotone area in φ, kept inside a shrinking bracket: a step that leaves it
// (flat slices near yMax) is replaced by bisection. sin φ and cos φ follow the steps by rotation (a
// short Taylor polynomial of the step). A step whose residual bound (Taylor: the quadratic model's
// residual, f³A''²/(2A'² − fA'')² for Halley's step, plus M₃|δ|³/6) is below half the tolerance is
// taken without evaluating the area again.
ProjectedSphereCap::Inversion ProjectedSphereCap::invertArea(double target) const {
  if (!(target > 0.0)) return {0.0, 0, 1.0};
  if (!(target < halfArea)) return {yMax, 0, cosPhiTangent};
  // First guess: two Newton steps on the cubic model from its root's lower bound target / w₀ (the
  // model is concave, so they stay below its root).
  double y = target * invStartWidth;
  for (int i = 0; i < 2; ++i) {
    const double y2 = y * y;
    y += (target - y * (startWidth - startCubic * y2)) / (startWidth - 3.0 * startCubic * y2);
  }
  if (!(y > 0.0 && y < yMax)) y = 0.5 * yMax;
  double sinPhi = std::min(1.0, y * invB);
  double cosPhi = sqrtNonNeg((1.0 - sinPhi) * (1.0 + sinPhi));
  double phi = arcsine(sinPhi, cosPhi);
  double lo = 0.0, hi = phiMax;
  const double ulps = 4 * 0x1p-52 * phiMax;
  int step = 0;
  while (step < kMaxInversionSteps) {
    ++step;
    const ArcSlice s = arcSlice(phi, sinPhi, cosPhi);
    const double f = s.area - target;
    if (std::fabs(f) <= inversionTolerance) break;
    (f < 0.0 ? lo : hi) = phi;
    // Halley's step −2 f A' / (2 A'² − f A'') in one division; Newton's where the correction would more
    // than double the step.
    // The residual the step leaves by Taylor: its quadratic model's, plus M₃|δ|³/6.
    const double halleyDenominator = 2.0 * s.dArea * s.dArea - f * s.d2Area;
    double delta, quadraticResidual;
    if (halleyDenominator > s.dArea * s.dArea) {
      const double inv = 1.0 / halleyDenominator;
      delta = -2.0 * f * s.dArea * inv;
      const double q = f * s.d2Area * inv;
      quadraticResidual = std::fabs(f) * q * q;
    } else {
      delta = -f / s.dArea;
      quadraticResidual = 0.5 * std::fabs(s.d2Area) * delta * delta;
    }
    bool bisected = false;
    if (!(phi + delta > lo && phi + delta < hi)) {
      delta = 0.5 * (lo + hi) - phi;
      bisected = true;
    }
    const SinCosD r =
        std::fabs(delta) <= 0.125 ? sinCosSmall(delta) : SinCosD{std::sin(delta), std::cos(delta)};
    const double nextSin = sinPhi * r.cos + cosPhi * r.sin;
    cosPhi = std::max(0.0, cosPhi * r.cos - sinPhi * r.sin);
    sinPhi = std::clamp(nextSin, 0.0, 1.0);
    phi += delta;
    if (bisected ? hi - lo <= ulps
                 : std::fabs(delta) <= ulps || quadraticResidual + areaThirdDerivativeBound *
                                                                       std::fabs(delta * delta * delta) *
                                                                       (1.0 / 6.0) <=
                                                   0.5 * inversionTolerance)
      break;
  }
  return {std::min(b * sinPhi, yMax), step, cosPhi};
}

ProjectedSphereCap::Direction ProjectedSphereCap::sampleDirection(Vec2 u) const {
  double dx, y;
  if (map == Map::Ellipse) {
    // Peters & Dachsbacher (I3D 2019): the unclipped ellipse is an affine image of the disk.
    const Vec2 disk = Warp::squareToConcentricDisk(u);
    dx = a * double(disk.x);
    y = b * double(disk.y);
  } else if (map == Map::CutDisks) {
    // Ureña & Georgiev's parallel map across x: u.x cuts off the area left of x, u.y places y on the
    // chord there. Left of the tangent points the ellipse's chord at X = −cos β; right of them the unit
    // disk's segment beyond x = cos γ, its area measured from the far end x = 1.
    const double area = double(u.x) * projectedSolidAngle;
    const double v = 2.0 * double(u.y) - 1.0;
    const bool ellipsePiece = area < ellipsePieceArea;
    const SinCosD angle =
        segmentAngle(ellipsePiece ? area * invAB : (1.0 - double(u.x)) * projectedSolidAngle);
    if (!ellipsePiece) {
      // The lift z = sin γ √(1 − v²), exactly (no cancellation next to the horizon).
      const double z = angle.sin * sqrtNonNeg((1.0 - v) * (1.0 + v));
      return {angle.cos * ex + (v * angle.sin) * ey + z * ez, z};
    }
    dx = -a * angle.cos;
    y = v * b * angle.sin;
  } else {
    // Ureña & Georgiev's parallel map across y: y from the inverted marginal area, x on its slice.
    const double v = 2.0 * double(u.x) - 1.0;
    const Inversion inv = invertArea(std::fabs(v) * halfArea);
    const double yAbs = inv.y, s2 = inv.cosPhi;
    const double width = std::max(0.0, circleGap(yAbs, sqrtNonNeg((1.0 - yAbs) * (1.0 + yAbs))) + a * s2);
    dx = -a * s2 + double(u.y) * width;
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
