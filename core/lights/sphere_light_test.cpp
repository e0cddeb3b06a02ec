#include "core/lights/sphere_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

namespace penumbra {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// ---- Closed form (re-derived here, independently of core/analysis/closed_forms.cpp) ----
// I(θ, α) with E = Le · I: θ between the receiver normal and the direction to the centre, α the
// angular radius of the sphere (sin α = r / d).
double atanMinusX(double w) {
  if (std::abs(w) >= 0.1) return std::atan(w) - w;
  // atan(w) − w = −w³/3 + w⁵/5 − w⁷/7 + ...
  const double w2 = w * w;
  double term = w * w2, sum = 0.0;
  for (int k = 1; k < 20; ++k) {
    sum += (k % 2 ? -term : term) / (2 * k + 1);
    term *= w2;
  }
  return sum;
}

double sphereIrradianceFactor(double cosT, double sinT, double sinA, double cosA) {
  if (cosT >= sinA) return kPiD * sinA * sinA * cosT;  // fully above
  if (cosT <= -sinA) return 0.0;                       // fully below
  const double cotA = cosA / sinA, cotT = cosT / sinT, tanA = sinA / cosA;
  const double y = -cotA * cotT;
  const double q = std::sqrt(std::max(0.0, 1.0 - y * y));
  const double w = tanA * sinT * q;
  return sinA * sinA * (cosT * std::acos(std::clamp(y, -1.0, 1.0)) + w) + atanMinusX(w);
}

TEST(SphereIrradianceClosedForm, KnownLimits) {
  // Centre on the horizon: α − sin α cos α.
  const double a = 0.4;
  EXPECT_NEAR(sphereIrradianceFactor(0.0, 1.0, std::sin(a), std::cos(a)), a - std::sin(a) * std::cos(a),
              1e-12);
  // On the surface: (π/2)(1 + cos θ).
  const double t = 1.0, sinA = 1.0 / (1.0 + 1e-12);
  EXPECT_NEAR(sphereIrradianceFactor(std::cos(t), std::sin(t), sinA, std::sqrt(1 - sinA * sinA)),
              kPiD / 2 * (1 + std::cos(t)), 1e-5);
  // Continuity at the horizon boundary cos θ = sin α.
  const double s = 0.3, c = std::sqrt(1 - s * s);
  const double eps = 1e-9;
  EXPECT_NEAR(sphereIrradianceFactor(s + eps, std::sqrt(1 - (s + eps) * (s + eps)), s, c),
              sphereIrradianceFactor(s - eps, std::sqrt(1 - (s - eps) * (s - eps)), s, c), 1e-7);
}

// ---- Monte Carlo set-up ---------------------------------------------------------------------------
struct Config {
  const char* name;
  double theta;     // angle of the centre from the receiver normal
  double sin2A;     // sin² α
  double gapOverR;  // if > 0: d = r (1 + gap) instead of d = 1 (x just outside the surface)
};

struct Scene {
  Vec3 x, n;
  SphereLight light;
  double truth;  // I(θ, α) from the float geometry, in double
};

Scene makeScene(const Config& c) {
  Scene s;
  s.x = Vec3(0.f);
  s.n = Vec3(0, 0, 1);
  double r, d;
  if (c.gapOverR > 0) {
    r = 1.0;
    d = 1.0 + c.gapOverR;
  } else {
    d = 1.0;
    r = std::sqrt(c.sin2A);
  }
  s.light.sphere.center = Vec3(float(d * std::sin(c.theta)), 0.f, float(d * std::cos(c.theta)));
  s.light.sphere.radius = float(r);
  s.light.radiance = Color3(1.f);
  if (c.gapOverR > 0) {
    // Put x just outside the float sphere along the centre direction (in double, then check).
    const DVec3 cc(s.light.sphere.center);
    const DVec3 dir = cc / glm::length(cc);
    s.x = Vec3(cc - dir * (double(s.light.sphere.radius) * (1.0 + c.gapOverR)));
  }
  // Truth from the float inputs.
  const DVec3 dc = DVec3(s.light.sphere.center) - DVec3(s.x);
  const double dd = glm::length(dc);
  const double rr = s.light.sphere.radius;
  const double cosT = glm::dot(dc / dd, DVec3(s.n));
  const double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
  const double sinA = rr / dd;
  const double cosA = std::sqrt(((dd - rr) / dd) * ((dd + rr) / dd));
  s.truth = sphereIrradianceFactor(cosT, sinT, sinA, cosA);
  return s;
}

struct Estimate {
  double mean, se;
  long invalid;
};

Vec2 uniform2(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.f, 1.f);
  return Vec2(std::min(u(rng), kOneMinusEpsilon), std::min(u(rng), kOneMinusEpsilon));
}

template <class Sampler>
Estimate estimate(const Scene& s, Sampler sampler, int n, uint32_t seed) {
  std::mt19937 rng(seed);
  double sum = 0, sum2 = 0;
  long invalid = 0;
  for (int i = 0; i < n; ++i) {
    LightSample ls = sampler(s.light, s.x, uniform2(rng));
    EXPECT_TRUE(std::isfinite(ls.pdf) && ls.pdf >= 0.f) << ls.pdf;
    EXPECT_TRUE(std::isfinite(ls.Le.x) && std::isfinite(ls.wi.x) && std::isfinite(ls.p.x) &&
                std::isfinite(ls.dist));
    double f = 0;
    if (ls.pdf > 0.f && !isBlack(ls.Le)) {
      EXPECT_NEAR(glm::length(ls.wi), 1.f, 1e-5f);
      f = double(ls.Le.x) * std::max(0.0, double(glm::dot(s.n, ls.wi))) / double(ls.pdf);
    }
    if (ls.pdf == 0.f) ++invalid;
    EXPECT_TRUE(std::isfinite(f));
    sum += f;
    sum2 += f * f;
  }
  const double mean = sum / n;
  const double var = std::max(0.0, sum2 / n - mean * mean);
  return {mean, std::sqrt(var / (n - 1)), invalid};
}

LightSample byArea(const SphereLight& l, const Vec3& x, Vec2 u) {
  return l.sampleArea(x, u);
}
LightSample bySolidAngle(const SphereLight& l, const Vec3& x, Vec2 u) {
  return l.sampleSolidAngle(x, u);
}

const Config kConfigs[] = {
    {"above", 0.5, 0.09, 0},
    {"straddling", 1.35, 0.25, 0},
    {"centreOnHorizon", kPiD / 2, 0.16, 0},
    {"tiny1e-6", 0.7, 1e-6, 0},
    {"tiny1e-10", 0.7, 1e-10, 0},
    {"tinyStraddling1e-6", kPiD / 2 - 5e-4, 1e-6, 0},
    {"nearSurface1e-6", 1.0, 0, 1e-6},
    {"nearSurfaceOnAxis", 0.0, 0, 1e-6},
    {"nearSurface1e-2", 1.0, 0, 1e-2},
};

// Area sampling from x at 1e-6·r outside the light sees the visible cap with probability
// (1 − sin α)/2 ≈ 5e-7: a few hundred thousand samples almost surely all land on the far side and the
// sample standard error is 0, so a 4-SE check is meaningless there. Area sampling is checked near the
// surface at 1e-2·r instead (visible fraction 0.5%); solid-angle sampling down to 1e-6·r.
bool areaSamplingTestable(const Config& c) {
  return c.gapOverR == 0 || c.gapOverR >= 1e-2;
}

// The estimators are unbiased: within 4 standard errors of the closed form, plus a floor for float
// rounding of the pdf and of wi (~1e-7 relative; only matters when the SE is tiny, e.g. solid-angle
// sampling of a distant light, whose estimate is nearly deterministic).
void expectAgrees(const Estimate& e, double truth, const char* what, const char* name) {
  if (std::getenv("PENUMBRA_VERBOSE"))
    std::printf("%-12s %-20s est %.9g ± %.3g truth %.9g (%.2f SE)\n", what, name, e.mean, e.se, truth,
                (e.mean - truth) / e.se);
  EXPECT_LE(std::abs(e.mean - truth), 4 * e.se + 1e-6 * truth)
      << what << " " << name << ": estimate " << e.mean << " ± " << e.se << " truth " << truth;
}

TEST(SphereLight, AreaAndSolidAngleEstimatesMatchClosedForm) {
  for (const Config& c : kConfigs) {
    Scene s = makeScene(c);
    ASSERT_GT(s.truth, 0.0) << c.name;
    Estimate solid = estimate(s, bySolidAngle, 100000, 12);
    EXPECT_EQ(solid.invalid, 0) << c.name;
    expectAgrees(solid, s.truth, "solid angle", c.name);
    if (!areaSamplingTestable(c)) continue;
    Estimate area = estimate(s, byArea, 400000, 11);
    EXPECT_EQ(area.invalid, 0) << c.name;
    expectAgrees(area, s.truth, "area", c.name);
    // Solid-angle sampling is never worse than area sampling here.
    EXPECT_LE(solid.se, area.se * 1.01) << c.name;
  }
}

TEST(SphereLight, BelowHorizonGivesExactlyZero) {
  Scene s = makeScene({"below", 2.2, 0.09, 0});  // cos θ = −0.59 < −sin α = −0.3
  EXPECT_EQ(s.truth, 0.0);
  EXPECT_EQ(estimate(s, byArea, 20000, 13).mean, 0.0);
  EXPECT_EQ(estimate(s, bySolidAngle, 20000, 14).mean, 0.0);
}

TEST(SphereLight, AreaSamplesFarSideFractionAndZeroContribution) {
  Scene s = makeScene({"above", 0.5, 0.09, 0});
  const double sinA = std::sqrt(0.09);
  std::mt19937 rng(15);
  const int n = 200000;
  int far = 0;
  for (int i = 0; i < n; ++i) {
    LightSample ls = s.light.sampleArea(s.x, uniform2(rng));
    EXPECT_EQ(ls.Le, s.light.eval(ls.p, ls.n, ls.wi));
    ASSERT_GT(ls.pdf, 0.f);
    ASSERT_TRUE(std::isfinite(ls.pdf));
    EXPECT_NEAR(glm::length(ls.p - s.light.sphere.center), s.light.sphere.radius, 1e-6f);
    EXPECT_NEAR(ls.pdf, s.light.pdfAreaAsSolidAngle(s.x, ls.p, ls.n), 1e-5f * ls.pdf);
    const float cosP = glm::dot(ls.n, glm::normalize(s.x - ls.p));
    if (std::abs(cosP) < 1e-6f) continue;  // on the silhouette, within rounding
    if (cosP < 0.f) {
      ++far;
      EXPECT_TRUE(isBlack(ls.Le));
      EXPECT_TRUE(isBlack(s.light.eval(ls.p, ls.n, ls.wi)));
    } else {
      EXPECT_EQ(ls.Le, s.light.radiance);
    }
  }
  // The visible cap is {n · (x − c) > r}: area fraction (1 − sin α)/2.
  const double expected = (1 + sinA) / 2;
  const double se = std::sqrt(expected * (1 - expected) / n);
  EXPECT_NEAR(double(far) / n, expected, 4 * se);
  EXPECT_FLOAT_EQ(s.light.pdfArea(), float(1 / (4 * kPiD * 0.09)));
}

// Directions and points of solid-angle samples: on the sphere, along wi, inside the cone, lit side.
TEST(SphereLight, SolidAngleSamplesAreConsistent) {
  for (const Config& c : kConfigs) {
    Scene s = makeScene(c);
    std::mt19937 rng(16);
    const DVec3 cc(s.light.sphere.center), xx(s.x);
    const double r = s.light.sphere.radius;
    for (int i = 0; i < 20000; ++i) {
      LightSample ls = s.light.sampleSolidAngle(s.x, uniform2(rng));
      ASSERT_GT(ls.pdf, 0.f) << c.name;
      ASSERT_TRUE(std::isfinite(ls.pdf) && std::isfinite(ls.dist)) << c.name;
      EXPECT_NEAR(glm::length(DVec3(ls.p) - cc), r, 1e-6 * std::max(r, glm::length(cc))) << c.name;
      // p lies along wi from x.
      const DVec3 along = xx + double(ls.dist) * DVec3(ls.wi);
      EXPECT_LT(glm::length(along - DVec3(ls.p)), 1e-5 * std::max(1.0, r)) << c.name;
      // The normal faces x, Le is the radiance, and the pdf function agrees.
      EXPECT_GE(glm::dot(ls.n, s.x - ls.p), -1e-5f * float(r)) << c.name;
      EXPECT_EQ(ls.Le, s.light.radiance);
      const float pdf = s.light.pdfSolidAngle(s.x, ls.wi);
      // Samples at the very rim may fall a rounding error outside the cone.
      if (pdf > 0.f) {
        EXPECT_FLOAT_EQ(pdf, ls.pdf) << c.name;
      }
    }
  }
}

// The solid-angle pdf integrates to 1 over the sphere of directions (midpoint rule in (cos θ, φ)
// around +z, with the cone axis tilted so the cone boundary is not aligned with the grid).
TEST(SphereLight, SolidAnglePdfIntegratesToOne) {
  struct Case {
    double theta, sin2A, gap;
  };
  for (Case k : {Case{0.3, 0.25, 0}, Case{1.2, 0.01, 0}, Case{0.7, 0, 1e-6}, Case{2.5, 0.5, 0}}) {
    Scene s = makeScene({"integral", k.theta, k.sin2A, k.gap});
    const int nc = 4000, np = 512;
    double sum = 0;
    for (int i = 0; i < nc; ++i) {
      const double z = -1 + 2 * (i + 0.5) / nc;
      const double rz = std::sqrt(1 - z * z);
      for (int j = 0; j < np; ++j) {
        const double phi = 2 * kPiD * (j + 0.5) / np;
        const Vec3 w(float(rz * std::cos(phi)), float(rz * std::sin(phi)), float(z));
        const float pdf = s.light.pdfSolidAngle(s.x, w);
        ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0.f);
        sum += pdf;
      }
    }
    const double integral = sum * (2.0 / nc) * (2 * kPiD / np);
    EXPECT_NEAR(integral, 1.0, 0.02) << k.theta << " " << k.sin2A;
  }
}

// Histogram of sampled directions in the cone's own coordinates: u = (1 − cos θ)/(1 − cos θmax) and
// φ are uniform on [0,1) × [0, 2π) exactly when the density is 1 / (2π (1 − cos θmax)). χ² on 10 × 10 bins.
TEST(SphereLight, SolidAngleHistogramIsUniformInTheCone) {
  for (const Config& c : {kConfigs[0], kConfigs[1], kConfigs[6]}) {
    Scene s = makeScene(c);
    const DVec3 dc = DVec3(s.light.sphere.center) - DVec3(s.x);
    const double d = glm::length(dc), r = s.light.sphere.radius;
    const DVec3 wc = dc / d;
    const double sin2Max = (r / d) * (r / d);
    const double oneMinusCosMax = sin2Max / (1 + std::sqrt(((d - r) / d) * ((d + r) / d)));
    DVec3 a = std::abs(wc.x) < 0.9 ? DVec3(1, 0, 0) : DVec3(0, 1, 0);
    const DVec3 sx = glm::normalize(glm::cross(a, wc)), sy = glm::cross(wc, sx);
    const int bins = 10, n = 200000;
    std::vector<int> hist(bins * bins, 0);
    std::mt19937 rng(17);
    for (int i = 0; i < n; ++i) {
      const DVec3 w(s.light.sampleSolidAngle(s.x, uniform2(rng)).wi);
      const double cosT = glm::dot(w, wc);
      const DVec3 cr = glm::cross(w, wc);
      const double sin2T = glm::dot(cr, cr);
      const double u = (sin2T / (1 + cosT)) / oneMinusCosMax;
      double phi = std::atan2(glm::dot(w, sy), glm::dot(w, sx));
      if (phi < 0) phi += 2 * kPiD;
      const int bu = std::min(bins - 1, int(u * bins)), bp = std::min(bins - 1, int(phi / (2 * kPiD) * bins));
      ASSERT_LE(u, 1.0 + 1e-4) << c.name;
      ++hist[bu * bins + bp];
    }
    double chi2 = 0;
    const double expected = double(n) / (bins * bins);
    for (int h : hist) chi2 += (h - expected) * (h - expected) / expected;
    // 99 degrees of freedom: P(χ² > 160) ≈ 1e-4.
    EXPECT_LT(chi2, 160.0) << c.name;
  }
}

TEST(SphereLight, InvalidConfigurationsGiveNoSampleNeverNaN) {
  std::mt19937 rng(18);
  SphereLight inside{Sphere{Vec3(0), 1.f}, Color3(1)};
  SphereLight zero{Sphere{Vec3(0, 0, 2), 0.f}, Color3(1)};
  SphereLight underflow{Sphere{Vec3(0, 0, 1), 1e-20f}, Color3(1)};  // 1 − cos θmax = 5e-41
  SphereLight farAway{Sphere{Vec3(0, 0, 1e30f), 1e-8f}, Color3(1)};
  for (int i = 0; i < 1000; ++i) {
    Vec2 u = uniform2(rng);
    Vec3 x(0.1f, -0.2f, 0.3f);
    for (const SphereLight* l : {&inside, &zero, &underflow, &farAway}) {
      LightSample ls = l->sampleSolidAngle(Vec3(0.1f, 0.f, 0.f), u);
      EXPECT_EQ(ls.pdf, 0.f);
      EXPECT_TRUE(isBlack(ls.Le));
      EXPECT_EQ(l->pdfSolidAngle(Vec3(0.1f, 0.f, 0.f), Vec3(0, 0, 1)), 0.f);
    }
    // Inside a one-sided light: area samples all face away, contributing 0.
    LightSample la = inside.sampleArea(x, u);
    EXPECT_TRUE(std::isfinite(la.pdf));
    EXPECT_TRUE(isBlack(la.Le));
    EXPECT_EQ(zero.sampleArea(x, u).pdf, 0.f);
  }
  // The narrowest cones that still fit: sin² = 1e-12 works and has a finite pdf.
  SphereLight tiny{Sphere{Vec3(0, 0, 1), 1e-6f}, Color3(1)};
  LightSample ls = tiny.sampleSolidAngle(Vec3(0), Vec2(0.3f, 0.6f));
  EXPECT_GT(ls.pdf, 0.f);
  EXPECT_TRUE(std::isfinite(ls.pdf));
  EXPECT_NEAR(ls.pdf, 1.0 / (kPiD * 1e-12), 1e-4 / (kPiD * 1e-12));
  EXPECT_NEAR(ls.dist, 1.f - 1e-6f, 1e-6f);
  // Exactly on the surface: the hemisphere toward the centre.
  SphereLight unit{Sphere{Vec3(0, 0, 1), 1.f}, Color3(1)};
  LightSample on = unit.sampleSolidAngle(Vec3(0), Vec2(0.5f, 0.5f));
  EXPECT_NEAR(on.pdf, 1.0 / (2 * kPiD), 1e-6);
  EXPECT_GE(on.wi.z, 0.f);
}

TEST(SphereLight, EvalIsOneSided) {
  SphereLight l{Sphere{Vec3(0), 1.f}, Color3(2, 3, 4)};
  EXPECT_EQ(l.eval(Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, -1)), Color3(2, 3, 4));
  EXPECT_EQ(l.eval(Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1)), Color3(0));
  EXPECT_EQ(l.eval(Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(1, 0, 0)), Color3(0));
}

// As in `penumbra check`'s light-sin2-underflow: 4π r² underflows for r = 1e-25 at distance 1; the
// area pdf (computed in double) must then make an invalid sample (pdf 0), never +inf.
TEST(SphereLight, AreaPdfOfAnUnderflowingLightIsNeverInfinite) {
  SphereLight light;
  light.sphere.center = Vec3(0.f, 0.f, 1.f);
  light.sphere.radius = 1e-25f;
  light.radiance = Color3(1e30f);
  for (Vec2 u : {Vec2(0.f), Vec2(0.25f, 0.5f), Vec2(0.5f), Vec2(1.f - 0x1p-24f)}) {
    LightSample s = light.sampleArea(Vec3(0.f), u);
    EXPECT_TRUE(std::isfinite(s.pdf)) << s.pdf;
    EXPECT_EQ(s.pdf, 0.f);
    EXPECT_EQ(light.pdfAreaAsSolidAngle(Vec3(0.f), light.sphere.center - Vec3(0, 0, 1e-25f), Vec3(0, 0, -1)),
              0.f);
  }
}

// As in `penumbra check`'s cone-sin2-1e-12: directions sampled at the rim of a very narrow cone round
// (as floats) to just outside it; pdfSolidAngle must still accept them (not return 0).
TEST(SphereLight, PdfSolidAngleAcceptsEveryDirectionItSampled) {
  for (double sin2 : {1e-8, 1e-12}) {
    SphereLight light;
    light.sphere.center = Vec3(2822.47265625f, 1881.6116943359375f, 9407.208984375f);
    light.sphere.radius = float(1e4 * std::sqrt(sin2));
    light.radiance = Color3(1.f);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> uni(0.f, 1.f);
    for (int i = 0; i < 20000; ++i) {
      Vec2 u(uni(rng), uni(rng));
      if (i < 4) u = Vec2(1.f - 0x1p-24f, 0.25f * float(i));  // exactly at the rim
      LightSample s = light.sampleSolidAngle(Vec3(0.f), u);
      ASSERT_GT(s.pdf, 0.f);
      ASSERT_EQ(light.pdfSolidAngle(Vec3(0.f), s.wi), s.pdf) << sin2 << " u " << u.x << "," << u.y;
    }
  }
}

}  // namespace
}  // namespace penumbra
