#include "core/lights/projected_cap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "core/lights/sphere_cap.h"
#include "core/math/frame.h"
#include "core/sampling/chi2.h"

namespace penumbra {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// A light whose centre is at angle `theta` from the normal +z of the shading point. Either d = 1 and
// sin²α = sin2A, or (gapOverR > 0) r = 1 and the shading point 1 + gapOverR radii from the centre.
struct Config {
  const char* name;
  double theta;
  double sin2A;
  double gapOverR = 0.0;
};

struct LightView {
  SphereLight light;
  Vec3 x{0.f}, n{0.f, 0.f, 1.f};
};

LightView makeView(const Config& c) {
  LightView s;
  const DVec3 dir(std::sin(c.theta), 0.0, std::cos(c.theta));
  if (c.gapOverR > 0) {
    s.light.sphere.center = Vec3(0.3f, -0.2f, 0.1f);
    s.light.sphere.radius = 1.f;
    s.x = Vec3(DVec3(s.light.sphere.center) - dir * (1.0 + c.gapOverR));
  } else {
    s.light.sphere.center = Vec3(dir);
    s.light.sphere.radius = float(std::sqrt(c.sin2A));
  }
  s.light.radiance = Color3(1.f);
  return s;
}

const Config kConfigs[] = {
    {"above", 0.5, 0.09},
    {"overhead", 0.0, 0.25},
    {"tangentAbove", std::acos(0.3 * (1 + 1e-9)), 0.09},
    {"straddlingAbove", 1.35, 0.25},
    {"straddlingBelow", kPiD / 2 + 0.3, 0.25},
    {"centreOnHorizon", kPiD / 2, 0.16},
    {"grazing89.9", kPiD / 2 - 0.0017453, 0.09},
    {"thinLensBelow", std::acos(-0.3 * (1 - 1e-3)), 0.09},
    {"tiny1e-6", 0.7, 1e-6},
    {"tiny1e-10", 0.7, 1e-10},
    {"tinyStraddling1e-6", kPiD / 2 - 5e-4, 1e-6},
    {"tinyStraddlingBelow1e-6", kPiD / 2 + 5e-4, 1e-6},
    {"tinyStraddling1e-12", kPiD / 2 - 3e-7, 1e-12},
    {"nearSurface1e-6", 1.0, 0, 1e-6},
    {"nearSurfaceOnAxis", 0.0, 0, 1e-6},
    {"nearSurfaceStraddling", 1.9, 0, 1e-6},
};

// The straddling configurations with the centre below the horizon (the lens map), and more of them.
std::vector<Config> lensConfigs() {
  std::vector<Config> out = {kConfigs[4], kConfigs[7], kConfigs[11]};
  for (double sa : {0.9, 0.5, 0.1, 1e-3})
    for (double f : {-0.9, -0.5, -0.1}) out.push_back({"lensSweep", std::acos(f * sa), sa * sa});
  out.push_back({"nearSurfaceLens", 1.5707963267948966 + 0.5, 0, 1e-6});
  return out;
}

// ---- the cap's own coordinates: s = (1 − cos γ)/(1 − cos α) ∈ [0, 1] and t = φ / 2π around the
// cap's axis; uniform solid angle on the cap is uniform on the square (dω = 2π (1 − cos α) ds dt).
struct CapFrame {
  DVec3 axis, e1, e2;
  double oneMinusCosAlpha;

  explicit CapFrame(const ProjectedSphereCap& cap) {
    axis = cap.toCenter / cap.distance;
    orthonormalBasis(axis, e1, e2);
    oneMinusCosAlpha = cap.sinAlpha * cap.sinAlpha / (1.0 + cap.cosAlpha);
  }
  Vec2 toSquare(const DVec3& w) const {
    const DVec3 c = glm::cross(w, axis);
    const double sin2 = glm::dot(c, c), cosG = glm::dot(w, axis);
    const double s = sin2 / (1.0 + cosG) / oneMinusCosAlpha;
    double phi = std::atan2(glm::dot(w, e2), glm::dot(w, e1));
    if (phi < 0) phi += 2 * kPiD;
    return Vec2(float(s), float(phi / (2 * kPiD)));
  }
  // s is kept 1e-9 inside the rim: the cap test exactly on it is decided by rounding, which would make
  // the density jagged along the whole line s = 1 (and the adaptive quadrature bisect it forever).
  DVec3 fromSquare(double s, double t) const {
    const double omc = std::min(s, 1.0 - 1e-9) * oneMinusCosAlpha;
    const double sinG = std::sqrt(std::max(0.0, omc * (2.0 - omc)));
    const double phi = 2 * kPiD * t;
    return (1.0 - omc) * axis + sinG * (std::cos(phi) * e1 + std::sin(phi) * e2);
  }
  double jacobian() const { return 2 * kPiD * oneMinusCosAlpha; }
};

TEST(ProjectedSphereCap, MappedAreaEqualsTheClosedForm) {
  // Sweep the straddling regime (and the configurations above): the map's own area (the two cut
  // disks' areas, or twice the lens's half) is sphere_cap.h's closed form Ω⊥ to rounding.
  std::vector<Config> cases(std::begin(kConfigs), std::end(kConfigs));
  for (double sa : {0.999, 0.9, 0.5, 0.1, 1e-3, 1e-5})
    for (double f : {-0.999, -0.9, -0.5, -0.1, 0.0, 0.1, 0.5, 0.9, 0.999})
      cases.push_back({"sweep", std::acos(f * sa), sa * sa});
  for (const Config& c : cases) {
    const LightView s = makeView(c);
    ProjectedSphereCap cap;
    ASSERT_TRUE(cap.init(s.light, s.x, s.n)) << c.name;
    if (!cap.straddling) continue;
    const double closed =
        sphereLightIrradianceFactor(cap.cosCentre, cap.sinCentre, cap.sinAlpha, cap.cosAlpha);
    // Both cancel for thin lenses (a cap just below the horizon): rounding of terms of size sin²α.
    const double tolerance = 1e-11 * closed + 1e-16 * kPiD * cap.sinAlpha * cap.sinAlpha;
    EXPECT_NEAR(cap.projectedSolidAngle, closed, tolerance)
        << c.name << " theta " << c.theta << " sin2 " << c.sin2A;
    if (cap.map == ProjectedSphereCap::Map::Lens) {
      EXPECT_NEAR(2 * cap.halfArea, cap.projectedSolidAngle, 1e-15 * cap.projectedSolidAngle);
      EXPECT_NEAR(cap.areaBelow(cap.yMax), cap.halfArea, 1e-15 * cap.halfArea);
    }
  }
}

TEST(ProjectedSphereCap, LensSliceWidthIsTheDerivativeOfTheArea) {
  // Not the thin lens: its area cancels to far more than the difference quotient's step.
  for (const Config& c : {kConfigs[4], kConfigs[11], lensConfigs().back()}) {
    const LightView s = makeView(c);
    ProjectedSphereCap cap;
    ASSERT_TRUE(cap.init(s.light, s.x, s.n));
    ASSERT_EQ(cap.map, ProjectedSphereCap::Map::Lens) << c.name;
    for (double f : {0.1, 0.3, 0.6, 0.9}) {
      const double y = f * cap.yMax, h = 1e-6 * cap.yMax;
      const double numeric = (cap.areaBelow(y + h) - cap.areaBelow(y - h)) / (2 * h);
      EXPECT_NEAR(numeric, cap.sliceWidth(y), 1e-6 * cap.sliceWidth(0.0)) << c.name << " y/yMax " << f;
    }
  }
}

// The inversion accepts a Halley step by Taylor's bound with M₃ = areaThirdDerivativeBound: it must
// bound |d³A/dφ³| (A(φ) = areaBelow(b sin φ)) everywhere on [0, phiMax], across the tangent too. Third
// differences, in the configurations where their rounding stays below a tenth of M₃ (the bound is
// within a factor 1.6 of the largest third difference for the small caps straddling above the horizon,
// so an M₃ too small by half fails).
TEST(ProjectedSphereCap, LensAreaThirdDerivativeBoundHolds) {
  int checked = 0;
  for (const Config& c : lensConfigs()) {
    const LightView s = makeView(c);
    ProjectedSphereCap cap;
    ASSERT_TRUE(cap.init(s.light, s.x, s.n));
    ASSERT_EQ(cap.map, ProjectedSphereCap::Map::Lens) << c.name;
    const double h = 1e-2 * cap.phiMax;
    const double noise = 64 * 0x1p-52 * cap.halfArea / (h * h * h);
    if (noise > 0.1 * cap.areaThirdDerivativeBound) continue;
    auto area = [&](double phi) { return cap.areaBelow(cap.b * std::sin(std::clamp(phi, 0.0, cap.phiMax))); };
    double worst = 0.0;
    for (int i = 0; i <= 200; ++i) {
      const double phi = 2 * h + (cap.phiMax - 4 * h) * i / 200;
      const double third =
          (area(phi + 2 * h) - 2 * area(phi + h) + 2 * area(phi - h) - area(phi - 2 * h)) / (2 * h * h * h);
      worst = std::max(worst, std::fabs(third));
      EXPECT_LE(std::fabs(third), 1.01 * cap.areaThirdDerivativeBound + noise) << c.name << " phi " << phi;
    }
    if (std::getenv("PENUMBRA_VERBOSE"))
      std::printf("%-26s max |A'''| / M3 = %.3f\n", c.name, worst / cap.areaThirdDerivativeBound);
    ++checked;
  }
  EXPECT_GE(checked, 4);
}

// Every sample: a unit direction inside the visible cap, the point where it meets the light facing x,
// pdf = cos θ / Ω⊥, and the pdf functions give it back.
TEST(ProjectedSphereCap, SamplesAreConsistent) {
  for (const Config& c : kConfigs) {
    const LightView s = makeView(c);
    ProjectedSphereCap cap;
    ASSERT_TRUE(cap.init(s.light, s.x, s.n)) << c.name;
    const DVec3 center(s.light.sphere.center), x(s.x);
    const double r = s.light.sphere.radius;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> uni(0.f, 1.f);
    for (int i = 0; i < 20000; ++i) {
      Vec2 u(uni(rng), uni(rng));
      if (i < 8) u = Vec2(i % 2 ? kOneMinusEpsilon : 0.f, i / 2 % 2 ? kOneMinusEpsilon : 0.5f);
      const ProjectedSphereCap::Direction d = cap.sampleDirection(u);
      ASSERT_NEAR(glm::length(d.w), 1.0, 1e-12) << c.name;
      ASSERT_GE(d.cosTheta, 0.0);
      ASSERT_NEAR(d.cosTheta, glm::dot(d.w, DVec3(s.n)), 1e-12);
      // Inside the cap up to rounding: sin γ ≤ sin α (1 + 1e-7) + 1e-15 (on the horizon the lift
      // z = √(z²) turns z²'s rounding into ~1e-8 of the cap's size).
      const DVec3 wc = glm::normalize(center - x);
      ASSERT_LE(glm::length(glm::cross(d.w, wc)), cap.sinAlpha * (1 + 1e-7) + 1e-15) << c.name << " " << i;
      const LightSample ls = cap.sample(u);
      if (d.cosTheta == 0.0) {  // a corner of the square mapped to a tangent point, on the horizon
        EXPECT_LT(i, 8);
        EXPECT_EQ(ls.pdf, 0.f);
        continue;
      }
      ASSERT_GT(ls.pdf, 0.f) << c.name << " " << i;
      ASSERT_TRUE(std::isfinite(ls.pdf) && std::isfinite(ls.dist));
      EXPECT_NEAR(double(ls.pdf), d.cosTheta / cap.projectedSolidAngle, 1e-6 * ls.pdf);
      EXPECT_NEAR(glm::length(DVec3(ls.p) - center), r, 1e-6 * std::max(r, glm::length(center)));
      EXPECT_LT(glm::length(x + double(ls.dist) * DVec3(ls.wi) - DVec3(ls.p)), 1e-5 * std::max(1.0, r));
      EXPECT_GE(glm::dot(ls.n, s.x - ls.p), -1e-5f * float(r)) << c.name;
      EXPECT_EQ(ls.Le, s.light.radiance);
      EXPECT_NEAR(cap.pdf(ls.wi), ls.pdf, 1e-5 * ls.pdf) << c.name << " " << i;
      if (i >= 8) {
        EXPECT_NEAR(cap.pdfDirection(d.w), d.cosTheta / cap.projectedSolidAngle, 1e-9 * ls.pdf);
      }
    }
  }
}

// The lens inversion's stop rule holds and it takes a bounded number of steps in every configuration,
// down to sin²α = 1e-12 just below the horizon and x 1e-6 r outside the light.
TEST(ProjectedSphereCap, LensInversionIsBoundedAndMeetsItsTolerance) {
  for (const Config& c : lensConfigs()) {
    const LightView s = makeView(c);
    ProjectedSphereCap cap;
    ASSERT_TRUE(cap.init(s.light, s.x, s.n));
    ASSERT_EQ(cap.map, ProjectedSphereCap::Map::Lens) << c.name;
    long total = 0;
    int worst = 0;
    const int n = 4096;
    for (int i = 0; i <= n; ++i) {
      const double target = cap.halfArea * i / n;
      const ProjectedSphereCap::Inversion inv = cap.invertArea(target);
      ASSERT_GE(inv.y, 0.0);
      ASSERT_LE(inv.y, cap.yMax);
      ASSERT_LE(inv.steps, ProjectedSphereCap::kMaxInversionSteps);
      total += inv.steps;
      worst = std::max(worst, inv.steps);
      // The stop rule, unless the step or the bracket reached a few ulps of yMax first.
      const double f = std::fabs(cap.areaBelow(inv.y) - target);
      if (f > cap.inversionTolerance) {
        EXPECT_LE(f, 4 * 0x1p-52 * cap.yMax * cap.sliceWidth(0.0) + cap.inversionTolerance)
            << c.name << " " << i;
      }
    }
    if (std::getenv("PENUMBRA_VERBOSE"))
      std::printf("%-26s inversion steps: mean %.2f, worst %d\n", c.name, double(total) / (n + 1), worst);
    EXPECT_LE(double(total) / (n + 1), 8.0) << c.name;
  }
}

// Stratification: the straddling maps are monotone along both coordinates of the square (so strata of
// the square stay disjoint, compact pieces of the region): for cut disks u.x moves x and u.y moves y,
// for the lens u.x moves y and u.y moves x.
TEST(ProjectedSphereCap, MapIsMonotoneInBothCoordinates) {
  for (const Config& c : {kConfigs[3], kConfigs[4], kConfigs[5], kConfigs[6], kConfigs[11], kConfigs[12]}) {
    const LightView s = makeView(c);
    ProjectedSphereCap cap;
    ASSERT_TRUE(cap.init(s.light, s.x, s.n));
    ASSERT_TRUE(cap.straddling);
    const bool cut = cap.map == ProjectedSphereCap::Map::CutDisks;
    const DVec3 alongUx = cut ? cap.ex : cap.ey, alongUy = cut ? cap.ey : cap.ex;
    for (float v : {0.1f, 0.5f, 0.93f}) {
      double prevFirst = -2, prevSecond = -2;
      for (int i = 0; i < 200; ++i) {
        const float t = (i + 0.5f) / 200;
        const double first = glm::dot(cap.sampleDirection(Vec2(t, v)).w, alongUx);
        EXPECT_GT(first, prevFirst) << c.name;
        prevFirst = first;
        const double second = glm::dot(cap.sampleDirection(Vec2(v, t)).w, alongUy);
        EXPECT_GT(second, prevSecond) << c.name;
        prevSecond = second;
      }
    }
  }
}

// Which map each straddling configuration takes: cut disks with the centre on or above the horizon,
// the lens below it.
TEST(ProjectedSphereCap, MapFollowsTheCentre) {
  for (const Config& c : kConfigs) {
    const LightView s = makeView(c);
    ProjectedSphereCap cap;
    ASSERT_TRUE(cap.init(s.light, s.x, s.n));
    if (!cap.straddling) {
      EXPECT_EQ(cap.map, ProjectedSphereCap::Map::Ellipse) << c.name;
      continue;
    }
    EXPECT_EQ(cap.map, cap.cosCentre >= 0 ? ProjectedSphereCap::Map::CutDisks : ProjectedSphereCap::Map::Lens)
        << c.name;
  }
}

// χ² of the sampled directions, binned in the cap's own coordinates, against the pdf (and, the test
// of the test, against the solid-angle pdf 1 / (2π (1 − cos α)), which must be rejected wherever
// cos θ varies over the cap enough for 10⁶ samples to see it).
struct Chi2Case {
  Config config;
  bool wrongPdfDetectable;
};

Chi2Result capChi2(const ProjectedSphereCap& cap, bool uniformPdf, int testCount) {
  const CapFrame frame(cap);
  Chi2Options o;
  o.sampleCount = 1'000'000;
  o.resolution = 40;
  o.seed = 7;
  o.testCount = testCount;
  auto sample = [&](Vec2 u) {
    Vec2 st = frame.toSquare(cap.sampleDirection(u).w);
    st.x = std::min(st.x, kOneMinusEpsilon);  // the rim, within rounding (checked in SamplesAreConsistent)
    return Vec3(st, 0.f);
  };
  auto pdf = [&](const Vec3& p) -> double {
    if (p.x < 0 || p.x > 1 || p.y < 0 || p.y > 1) return 0.0;
    if (uniformPdf) return 1.0;
    return cap.pdfDirection(frame.fromSquare(p.x, p.y)) * frame.jacobian();
  };
  return chi2Test(Chi2Domain::square(0.0, 1.0), sample, pdf, o);
}

const Chi2Case kChi2Cases[] = {
    {kConfigs[0], true},  {kConfigs[1], true},  {kConfigs[3], true},  {kConfigs[4], true},
    {kConfigs[5], true},  {kConfigs[6], true},  {kConfigs[7], true},  {kConfigs[8], false},
    {kConfigs[9], false}, {kConfigs[10], true}, {kConfigs[11], true}, {kConfigs[12], true},
    {kConfigs[13], true}, {kConfigs[14], true}, {kConfigs[15], true},
};
constexpr int kChi2Count = int(std::size(kChi2Cases));

TEST(ProjectedSphereCap, Chi2InTheCapFrame) {
  for (const Chi2Case& k : kChi2Cases) {
    const LightView s = makeView(k.config);
    ProjectedSphereCap cap;
    ASSERT_TRUE(cap.init(s.light, s.x, s.n));
    const Chi2Result r = capChi2(cap, false, kChi2Count);
    if (std::getenv("PENUMBRA_VERBOSE"))
      std::printf("%-26s %s chi2 %10.2f dof %5d p %.4f %s\n", k.config.name, cap.straddling ? "S" : "E",
                  r.chi2, r.dof, r.pValue, r.accepted ? "accept" : "reject");
    EXPECT_TRUE(r.accepted) << k.config.name << ": " << r.message << " p = " << r.pValue;
  }
}

TEST(ProjectedSphereCap, Chi2RejectsTheSolidAnglePdf) {
  for (const Chi2Case& k : kChi2Cases) {
    if (!k.wrongPdfDetectable) continue;
    const LightView s = makeView(k.config);
    ProjectedSphereCap cap;
    ASSERT_TRUE(cap.init(s.light, s.x, s.n));
    const Chi2Result r = capChi2(cap, true, kChi2Count);
    if (std::getenv("PENUMBRA_VERBOSE"))
      std::printf("%-26s wrong pdf: chi2 %10.2f dof %5d p %.3g %s\n", k.config.name, r.chi2, r.dof, r.pValue,
                  r.accepted ? "accept" : "reject");
    EXPECT_FALSE(r.accepted) << k.config.name;
  }
}

// The pdf integrates to 1 over the visible cap (adaptive quadrature in the cap's coordinates).
TEST(ProjectedSphereCap, PdfIntegratesToOne) {
  for (const Config& c : kConfigs) {
    const LightView s = makeView(c);
    ProjectedSphereCap cap;
    ASSERT_TRUE(cap.init(s.light, s.x, s.n));
    const CapFrame frame(cap);
    const double integral = integratePdf(
        Chi2Domain::square(0.0, 1.0),
        [&](const Vec3& p) { return cap.pdfDirection(frame.fromSquare(p.x, p.y)) * frame.jacobian(); }, 40);
    EXPECT_NEAR(integral, 1.0, 1e-6) << c.name;
  }
}

TEST(ProjectedSphereCap, NothingToSample) {
  SphereLight light{Sphere{Vec3(0, 0, 2), 1.f}, Color3(1)};
  ProjectedSphereCap cap;
  EXPECT_FALSE(cap.init(light, Vec3(0, 0, 2.5f), Vec3(0, 0, 1)));  // inside
  EXPECT_FALSE(cap.init(light, Vec3(0), Vec3(0, 0, -1)));          // below the horizon
  EXPECT_FALSE(cap.init(SphereLight{Sphere{Vec3(0, 0, 2), 0.f}, Color3(1)}, Vec3(0), Vec3(0, 0, 1)));
  EXPECT_FALSE(cap.init(SphereLight{Sphere{Vec3(0, 0, 1), 1e-20f}, Color3(1)}, Vec3(0), Vec3(0, 0, 1)));
  // On the surface: the hemisphere towards the centre, Ω⊥ = (π/2)(1 + cos θ).
  SphereLight unit{Sphere{Vec3(0, 0, 1), 1.f}, Color3(1)};
  ASSERT_TRUE(cap.init(unit, Vec3(0), Vec3(0, 0, 1)));
  EXPECT_NEAR(cap.projectedSolidAngle, kPiD, 1e-12);
  ASSERT_TRUE(cap.init(unit, Vec3(0), glm::normalize(Vec3(1, 0, 1))));
  EXPECT_NEAR(cap.projectedSolidAngle, kPiD / 2 * (1 + std::sqrt(0.5)), 1e-6);
  EXPECT_EQ(cap.map, ProjectedSphereCap::Map::CutDisks);
}

}  // namespace
}  // namespace penumbra
