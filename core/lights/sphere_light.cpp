#include "core/lights/sphere_light.h"

#include <cmath>

#include "core/math/frame.h"
#include "core/math/sincos_turns.h"
#include "core/sampling/warp.h"

namespace penumbra {
namespace {

constexpr double kMinOneMinusCos = SphereLight::kMinOneMinusCos;
constexpr double kMaxPdf = SphereLight::kMaxPdf;
constexpr double kDirectionSlack = SphereLight::kDirectionSlack;

// The cone subtended by the sphere at x; false if x is inside or the cone is degenerate.
struct Cone {
  DVec3 wc;            // unit, x → centre
  double d;            // |c − x|
  double sin2Max;      // r² / d²
  double cosMax;       // √((d − r)/d · (d + r)/d)
  double oneMinusCos;  // sin² / (1 + cos)
};

bool subtendedCone(const Sphere& s, const Vec3& x, Cone& cone) {
  const double r = s.radius;
  const DVec3 dc = DVec3(s.center) - DVec3(x);
  const double d = std::sqrt(glm::dot(dc, dc));  // float inputs: the squares are exact in double
  if (!(r > 0.0) || !(d >= r) || !std::isfinite(d)) return false;
  const double invD = 1.0 / d;
  cone.wc = dc * invD;
  cone.d = d;
  const double sinMax = r * invD;
  cone.sin2Max = sinMax * sinMax;
  cone.cosMax = std::sqrt((d - r) * (d + r)) * invD;
  cone.oneMinusCos = cone.sin2Max / (1.0 + cone.cosMax);
  return cone.oneMinusCos >= kMinOneMinusCos;
}

}  // namespace

float SphereLight::pdfArea() const {
  const float a = area();
  return a > 0.f ? 1.f / a : 0.f;
}

LightSample SphereLight::sampleArea(const Vec3& x, Vec2 u) const {
  LightSample ls;
  if (!(sphere.radius > 0.f)) return ls;
  const Vec3 n = Warp::squareToUniformSphere(u);
  ls.n = n;
  ls.p = sphere.center + sphere.radius * n;
  const DVec3 toP = DVec3(ls.p) - DVec3(x);  // exact: float inputs
  const double dist2 = glm::dot(toP, toP);
  const double nDotToP = glm::dot(DVec3(n), toP);  // −cos θp · dist, θp between n and the way back to x
  if (!(dist2 > 0.0) || nDotToP == 0.0) return ls;
  // pdf = dist² / (4πr² |cos θp|) = dist³ / (4πr² |n · toP|): one square root, and the two divisions
  // below do not wait for each other (this runs once per camera sample).
  const double dist = std::sqrt(dist2);
  const double invDist = 1.0 / dist;
  const double pdf = dist2 * dist / (4.0 * kPiD * double(sphere.radius) * sphere.radius * std::fabs(nDotToP));
  if (!(pdf <= kMaxPdf)) return ls;  // beyond float: invalid, never an infinite pdf
  ls.wi = Vec3(toP * invDist);
  ls.dist = static_cast<float>(dist);
  ls.pdf = static_cast<float>(pdf);
  // eval's one-sided test on the unrounded direction: far side (cos θp ≤ 0) emits nothing.
  ls.Le = nDotToP < 0.0 ? radiance : Color3(0.f);
  return ls;
}

float SphereLight::pdfAreaAsSolidAngle(const Vec3& x, const Vec3& p, const Vec3& n) const {
  if (!(sphere.radius > 0.f)) return 0.f;
  const DVec3 toX = DVec3(x) - DVec3(p);
  const double d2 = glm::dot(toX, toX);
  if (!(d2 > 0.0)) return 0.f;
  const double cosP = glm::dot(DVec3(n), toX) / std::sqrt(d2);
  if (cosP == 0.0) return 0.f;
  const double pdf = d2 / (4.0 * kPiD * double(sphere.radius) * sphere.radius * std::abs(cosP));
  return pdf <= kMaxPdf ? static_cast<float>(pdf) : 0.f;
}

LightSample SphereLight::sampleSolidAngle(const Vec3& x, Vec2 u) const {
  LightSample ls;
  Cone cone;
  if (!subtendedCone(sphere, x, cone)) return ls;

  // Uniform in the cone: 1 − cos θ = u0 (1 − cos θmax), everything from 1 − cos θ (no cancellation).
  const double oneMinusCosT = double(u.x) * cone.oneMinusCos;
  const double cosT = 1.0 - oneMinusCosT;
  const double sin2T = oneMinusCosT * (2.0 - oneMinusCosT);
  const double sinT = std::sqrt(sin2T);
  // φ only needs float precision (it sets no cancellation-prone quantity).
  const SinCos phi = sinCosTurns(u.y);
  const double cosPhi = phi.cos, sinPhi = phi.sin;

  // Angle α at the centre between (x − c) and (p − c) (pbrt-v4):
  // cos α = sin²θ / sin θmax + cos θ √(1 − sin²θ / sin²θmax), with 1 / sin θmax = d / r.
  const double invSinMax = cone.d / double(sphere.radius);
  const double ratio = sin2T * invSinMax;  // sin²θ / sin θmax
  const double cosA = ratio + cosT * std::sqrt(std::max(0.0, 1.0 - ratio * invSinMax));
  const double sinA = std::sqrt(std::max(0.0, 1.0 - cosA * cosA));

  DVec3 s, t;
  orthonormalBasis(cone.wc, s, t);
  const DVec3 lateral = cosPhi * s + sinPhi * t;
  const DVec3 wi = sinT * lateral + cosT * cone.wc;
  const DVec3 n = sinA * lateral - cosA * cone.wc;  // faces x: n·(−wc) = cos α ≥ 0
  const DVec3 p = DVec3(sphere.center) + double(sphere.radius) * n;

  ls.p = Vec3(p);
  ls.n = Vec3(n);    // unit by construction (sin²α + cos²α = 1, orthonormal basis)
  ls.wi = Vec3(wi);  // unit by construction
  ls.dist = static_cast<float>(glm::length(p - DVec3(x)));
  ls.pdf = static_cast<float>(1.0 / ((2.0 * kPiD) * cone.oneMinusCos));
  ls.Le = radiance;
  return ls;
}

float SphereLight::pdfSolidAngle(const Vec3& x, const Vec3& wi) const {
  Cone cone;
  if (!subtendedCone(sphere, x, cone)) return 0.f;
  const DVec3 w(wi);
  const double cosW = glm::dot(w, cone.wc);
  if (cosW <= 0.0) return 0.f;
  // Inside the cone iff sin² of the angle to the axis ≤ sin²θmax (accurate for narrow cones).
  const DVec3 c = glm::cross(w, cone.wc);
  const double sin2W = glm::dot(c, c) / glm::dot(w, w);
  const double sinMax = std::sqrt(cone.sin2Max) + kDirectionSlack;
  if (sin2W > sinMax * sinMax) return 0.f;
  return static_cast<float>(1.0 / ((2.0 * kPiD) * cone.oneMinusCos));
}

}  // namespace penumbra
