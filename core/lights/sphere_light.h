// A uniform, one-sided (outward) spherical area light, with the assignment's three measures:
// uniform area sampling, uniform sampling of the subtended cone (solid angle), and their pdfs.
// Plain struct, no virtuals: integrators pick the sampler once per pass.
#pragma once

#include "core/geometry/sphere.h"
#include "core/lights/light_sample.h"

namespace penumbra {

struct SphereLight {
  Sphere sphere;
  Color3 radiance{0.f};
  // Index of this sphere in SceneGeometry (-1: not in it), so its own shadow rays can skip it.
  int32_t geometryIndex = -1;

  // Below this 1 − cos θmax the cone pdf 1 / (2π (1 − cos θmax)) would not fit in a float.
  static constexpr double kMinOneMinusCos = 0x1p-120;
  // Largest density returned as a float; an area pdf beyond it (a light so small that 4π r²
  // underflows) marks the sample invalid rather than returning +inf.
  static constexpr double kMaxPdf = 3.4028234663852886e38;
  // Float directions carry ~2^-24 relative error per component: a sampled direction at the cone's
  // edge may round up to a few 2^-24 outside it. pdfSolidAngle accepts sin θ up to sin θmax + 2^-22,
  // so it never returns 0 for a direction sampleSolidAngle produced (matters for cones of
  // sin²θmax ≲ 1e-8).
  static constexpr double kDirectionSlack = 0x1p-22;

  float area() const { return 4.f * kPi * sphere.radius * sphere.radius; }
  // Area density of sampleArea: 1 / (4π r²) (0 for a radius-0 light).
  float pdfArea() const;

  // Uniform point on the whole sphere. sample.pdf is the SOLID-ANGLE density at x of the sampled
  // direction, pdfArea · d² / |cos θp| (θp between n and the direction back to x). Far-side points
  // (n·(x − p) ≤ 0) are returned with Le = 0: they are genuine samples that contribute nothing.
  // pdf = 0 (invalid) for a radius-0 light, when cos θp == 0 exactly (a measure-zero tangent), or when
  // the density would not fit in a float (4π r² underflowing: r ≲ 1e-19 d); never +inf.
  LightSample sampleArea(const Vec3& x, Vec2 u) const;
  // Solid-angle density at x of sampleArea producing point p with normal n: pdfArea · d² / |cos θp|
  // (0 when cos θp == 0 or p == x).
  float pdfAreaAsSolidAngle(const Vec3& x, const Vec3& p, const Vec3& n) const;

  // Uniform direction in the cone subtended by the sphere at x (pbrt-v4 Sphere::Sample(ctx)). The
  // point p is computed from the cone angle analytically (cos α formula), not by ray casting.
  // sample.pdf = 1 / (2π (1 − cos θmax)) w.r.t. solid angle, with 1 − cos θmax = sin²θmax / (1 + cos θmax).
  // Every sample sees the lit (outward) side, so Le = radiance. Invalid (pdf = 0): x strictly inside
  // the sphere (one-sided emitter, no light inside), radius 0, or a cone so narrow that its pdf
  // overflows float (1 − cos θmax < 2^-120). x on the surface gives the hemisphere toward the centre.
  // The cone is sampled here in double rather than through Warp::squareToUniformConeSin2: mapping a
  // direction to the point on the sphere needs sin²θ of the sample to full relative precision, which
  // a float unit vector does not carry for narrow cones (sin²θmax down to 1e-12 and below).
  LightSample sampleSolidAngle(const Vec3& x, Vec2 u) const;
  // Density of sampleSolidAngle: 1 / (2π (1 − cos θmax)) for wi inside the cone, 0 outside or when
  // sampleSolidAngle would return an invalid sample. wi must be unit length. The cone test allows
  // sin θ up to sin θmax + 2^-22 (the rounding of a float direction), so every direction that
  // sampleSolidAngle returns gets its density back, even for sin²θmax = 1e-12.
  float pdfSolidAngle(const Vec3& x, const Vec3& wi) const;

  // Radiance leaving p (normal n) toward a point that sees it along wi (from that point toward p):
  // `radiance` if the light faces it (dot(n, −wi) > 0), else 0. One-sided, outward.
  Color3 eval(const Vec3& /*p*/, const Vec3& n, const Vec3& wi) const {
    return glm::dot(n, wi) < 0.f ? radiance : Color3(0.f);
  }
};

}  // namespace penumbra
