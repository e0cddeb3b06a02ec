#include "core/lights/light_selection.h"

#include <gtest/gtest.h>

#include <boost/math/special_functions/gamma.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "core/lights/light_bvh.h"
#include "core/sampling/chi2.h"
#include "core/sampling/rng.h"

namespace penumbra {
namespace {

// Pearson χ² of observed counts against expected probabilities: cells expecting fewer than 5 draws
// are pooled into one; a cell with observations but probability 0 rejects outright.
bool discreteChi2Accepts(const std::vector<uint64_t>& observed, const std::vector<double>& pmf, uint64_t n,
                         double alpha, std::string* why = nullptr) {
  double chi2 = 0.0, pooledObs = 0.0, pooledExp = 0.0;
  int cells = 0;
  for (size_t i = 0; i < pmf.size(); ++i) {
    const double e = pmf[i] * double(n);
    if (pmf[i] == 0.0 && observed[i] > 0) {
      if (why) *why = "item " + std::to_string(i) + " has pmf 0 but was drawn";
      return false;
    }
    if (e < 5.0) {
      pooledObs += double(observed[i]);
      pooledExp += e;
      continue;
    }
    chi2 += (double(observed[i]) - e) * (double(observed[i]) - e) / e;
    ++cells;
  }
  if (pooledExp > 0.0) {
    chi2 += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp;
    ++cells;
  }
  if (cells < 2) return true;
  const double p = boost::math::gamma_q(0.5 * (cells - 1), 0.5 * chi2);
  if (why)
    *why = "chi2 " + std::to_string(chi2) + " dof " + std::to_string(cells - 1) + " p " + std::to_string(p);
  return p > alpha;
}

// The 53-bit uniform the integrators pass (two sampler dimensions combined).
double uniform53(Rng& rng) {
  return rng.nextDouble();
}

std::vector<SphereLight> randomLights(int n, uint64_t seed, float spread = 10.f) {
  std::mt19937 rng(static_cast<uint32_t>(seed));
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<SphereLight> lights(static_cast<size_t>(n));
  for (SphereLight& l : lights) {
    l.sphere.center = Vec3(u(rng) - 0.5f, u(rng), u(rng) - 0.5f) * spread + Vec3(0, 0.5f, 0);
    l.sphere.radius = 0.02f + 0.3f * u(rng);
    l.radiance = Color3(1.f + 50.f * u(rng) * u(rng));
  }
  return lights;
}

// ---- alias table --------------------------------------------------------------------------------

TEST(AliasTable, RealisedProbabilitiesEqualThePmfsAndSumToOne) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n : {1, 2, 3, 17, 1000}) {
    std::vector<double> w(static_cast<size_t>(n));
    for (double& x : w) x = u(rng) < 0.2 ? 0.0 : std::pow(u(rng), 4.0);
    w[0] = 1.0;
    const AliasTable t = makeAliasTable(w);
    // What sample() draws: bin i keeps its item with probability keep, else its alias.
    std::vector<double> realised(static_cast<size_t>(n), 0.0);
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      realised[size_t(i)] += t.bins[size_t(i)].keep / n;
      realised[t.bins[size_t(i)].alias] += (1.0 - t.bins[size_t(i)].keep) / n;
      sum += t.pmf(uint32_t(i));
    }
    EXPECT_NEAR(sum, 1.0, 1e-14 * n);
    double total = 0.0;
    for (double x : w) total += x;
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(realised[size_t(i)], t.pmf(uint32_t(i)), 1e-14) << n << " " << i;
      EXPECT_NEAR(t.pmf(uint32_t(i)), w[size_t(i)] / total, 1e-15);
      if (w[size_t(i)] == 0.0) EXPECT_EQ(realised[size_t(i)], 0.0);
    }
  }
}

TEST(AliasTable, DegenerateWeights) {
  const std::vector<double> none = {0.0, 0.0, 0.0, 0.0};
  const AliasTable zero = makeAliasTable(none);
  for (uint32_t i = 0; i < 4; ++i) EXPECT_EQ(zero.pmf(i), 0.25);
  const std::vector<double> bad = {NAN, -1.0, INFINITY, 2.0};
  const AliasTable t = makeAliasTable(bad);
  EXPECT_EQ(t.pmf(3), 1.0);
  for (double u : {0.0, 0.3, 0.6, 0.999999, 0x1.fffffffffffffp-1}) EXPECT_EQ(t.sample(u), 3u);
  EXPECT_EQ(makeAliasTable(std::vector<double>{}).size(), 0u);
}

TEST(AliasTable, DrawsFollowThePmf) {
  std::vector<double> w;
  for (int i = 0; i < 50; ++i) w.push_back(i % 7 == 0 ? 0.0 : 1.0 + (i % 5) * (i % 3));
  const AliasTable t = makeAliasTable(w);
  Rng rng(3, 4);
  const uint64_t n = 400000;
  std::vector<uint64_t> counts(w.size(), 0);
  for (uint64_t k = 0; k < n; ++k) ++counts[t.sample(uniform53(rng))];
  std::vector<double> pmf;
  for (uint32_t i = 0; i < w.size(); ++i) pmf.push_back(t.pmf(i));
  std::string why;
  EXPECT_TRUE(discreteChi2Accepts(counts, pmf, n, 0.01, &why)) << why;
  // A deliberately wrong pmf (uniform over the non-zero items) is rejected.
  std::vector<double> wrong(w.size(), 0.0);
  for (size_t i = 0; i < w.size(); ++i) wrong[i] = w[i] > 0.0 ? 1.0 / 42.0 : 0.0;
  EXPECT_FALSE(discreteChi2Accepts(counts, wrong, n, 0.01));
}

// ---- uniform and power selection ------------------------------------------------------------------

TEST(LightSelection, UniformAndPowerPmfsSumToOneAndMatchTheirDraws) {
  const auto lights = randomLights(30, 5);
  const UniformLightSelection uniform = makeUniformLightSelection(summarizeLights(lights));
  const PowerLightSelection power = makePowerLightSelection(summarizeLights(lights));
  double su = 0.0, sp = 0.0, total = 0.0;
  for (const SphereLight& l : lights) total += sphereLightPower(l);
  for (uint32_t i = 0; i < lights.size(); ++i) {
    su += uniform.pmf(Vec3(0), Vec3(0), i);
    sp += power.pmf(Vec3(0), Vec3(0), i);
    EXPECT_NEAR(power.pmf(Vec3(0), Vec3(0), i), sphereLightPower(lights[i]) / total, 1e-15);
  }
  EXPECT_NEAR(su, 1.0, 1e-14);
  EXPECT_NEAR(sp, 1.0, 1e-14);
  Rng rng(6, 7);
  const uint64_t n = 300000;
  std::vector<uint64_t> cu(lights.size(), 0), cp(lights.size(), 0);
  std::vector<double> pu, pp;
  for (uint32_t i = 0; i < lights.size(); ++i) {
    pu.push_back(uniform.pmf(Vec3(0), Vec3(0), i));
    pp.push_back(power.pmf(Vec3(0), Vec3(0), i));
  }
  for (uint64_t k = 0; k < n; ++k) {
    const LightPick a = uniform.pick(Vec3(0), Vec3(0), uniform53(rng));
    const LightPick b = power.pick(Vec3(0), Vec3(0), uniform53(rng));
    ASSERT_EQ(a.pmf, pu[a.light]);
    ASSERT_EQ(b.pmf, pp[b.light]);
    ++cu[a.light];
    ++cp[b.light];
  }
  std::string why;
  EXPECT_TRUE(discreteChi2Accepts(cu, pu, n, 0.01 / 2, &why)) << why;
  EXPECT_TRUE(discreteChi2Accepts(cp, pp, n, 0.01 / 2, &why)) << why;
  EXPECT_FALSE(discreteChi2Accepts(cp, pu, n, 0.01 / 2));  // power draws are not uniform
}

TEST(LightSelection, PowerIsZeroExactlyForDarkOrPointLikeLights) {
  SphereLight l;
  l.sphere.radius = 0.5f;
  l.radiance = Color3(3.f, 0.f, 0.f);
  EXPECT_NEAR(sphereLightPower(l), 4.0 * M_PI * M_PI * 0.25 * 1.0, 1e-12);
  l.radiance = Color3(0.f);
  EXPECT_EQ(sphereLightPower(l), 0.0);
  l.radiance = Color3(1.f);
  l.sphere.radius = 0.f;
  EXPECT_EQ(sphereLightPower(l), 0.0);
  EXPECT_EQ(makeUniformLightSelection(summarizeLights({})).pick(Vec3(0), Vec3(0), 0.5).pmf, 0.0);
  EXPECT_EQ(makePowerLightSelection(summarizeLights({})).pick(Vec3(0), Vec3(0), 0.5).pmf, 0.0);
}

// ---- light BVH -------------------------------------------------------------------------------------

struct ShadingPointSample {
  Vec3 p, n;
};

std::vector<ShadingPointSample> shadingPoints(int count, uint64_t seed) {
  std::mt19937 rng(static_cast<uint32_t>(seed));
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<ShadingPointSample> out;
  for (int i = 0; i < count; ++i) {
    ShadingPointSample s;
    s.p = Vec3(u(rng), 0.6f * u(rng) + 0.5f, u(rng)) * 8.f;
    switch (i % 3) {
      case 0:
        s.n = Vec3(0, 1, 0);  // a floor
        break;
      case 1:
        s.n = glm::normalize(Vec3(u(rng), u(rng), u(rng)) + Vec3(1e-3f));
        break;
      default:
        s.n = Vec3(0);  // no normal
    }
    out.push_back(s);
  }
  return out;
}

// Whether any point of the sphere lies strictly above the tangent plane at p (so it may light p).
bool canLight(const SphereLight& l, const Vec3& p, const Vec3& n) {
  if (n == Vec3(0)) return true;
  return double(glm::dot(DVec3(n), DVec3(l.sphere.center) - DVec3(p))) > -double(l.sphere.radius);
}

void expectConsistentBvh(const std::vector<SphereLight>& lights, const LightBvh& bvh, int points,
                         uint64_t seed) {
  Rng rng(seed, 1);
  for (const ShadingPointSample& s : shadingPoints(points, seed)) {
    double sum = 0.0;
    for (uint32_t i = 0; i < lights.size(); ++i) {
      const double pmf = bvh.pmf(s.p, s.n, i);
      ASSERT_TRUE(std::isfinite(pmf) && pmf >= 0.0 && pmf <= 1.0);
      sum += pmf;
      // Conservative: a light that can reach p is never given probability 0.
      if (sphereLightPower(lights[i]) > 0.0 && canLight(lights[i], s.p, s.n)) EXPECT_GT(pmf, 0.0) << i;
    }
    if (sum > 0.0) {
      EXPECT_NEAR(sum, 1.0, 1e-12);
    }
    if (s.n == Vec3(0)) EXPECT_NEAR(sum, 1.0, 1e-12);  // without a horizon every light may reach p
    for (int k = 0; k < 20; ++k) {
      const LightPick pick = bvh.pick(s.p, s.n, uniform53(rng));
      if (sum == 0.0) {
        EXPECT_EQ(pick.pmf, 0.0);
        continue;
      }
      ASSERT_GT(pick.pmf, 0.0);
      EXPECT_NEAR(pick.pmf, bvh.pmf(s.p, s.n, pick.light), 1e-12 * pick.pmf);
    }
  }
}

TEST(LightBvh, PmfsSumToOneAndMatchPicksAtManyShadingPoints) {
  for (int n : {1, 2, 3, 10, 257}) {
    const auto lights = randomLights(n, 10 + uint64_t(n));
    const LightBvh bvh = makeLightBvh(summarizeLights(lights));
    EXPECT_EQ(bvh.nodes.size(), size_t(2 * n - 1));
    expectConsistentBvh(lights, bvh, 300, uint64_t(n));
  }
}

// Lights whose centroids span more than the largest float (at ±1e38 and beyond) still build a tree of
// every light: the split's bucket ratios are NaN or infinite there (UBSan checks the cast to a bucket).
TEST(LightBvh, CentroidsSpanningAnInfiniteExtentStillBuild) {
  std::vector<LightSummary> lights;
  for (const float x : {-3e38f, -1e38f, 0.f, 1.f, 1e38f, 3e38f, INFINITY}) {
    LightSummary l;
    l.centroid = Vec3(x, 0.5f * x, 1.f);
    l.box.expand(l.centroid);
    l.power = 1.0;
    lights.push_back(l);
  }
  const LightBvh bvh = makeLightBvh(lights);
  ASSERT_EQ(bvh.nodes.size(), 2 * lights.size() - 1);
  std::vector<int> leaves(lights.size(), 0);
  for (const LightBvhNode& node : bvh.nodes)
    if (node.leaf) ++leaves[node.child];
  for (int count : leaves) EXPECT_EQ(count, 1);
}

TEST(LightBvh, DrawsFollowThePmf) {
  const auto lights = randomLights(40, 11);
  const LightBvh bvh = makeLightBvh(summarizeLights(lights));
  const auto points = shadingPoints(3, 12);
  for (const ShadingPointSample& s : points) {
    std::vector<double> pmf;
    for (uint32_t i = 0; i < lights.size(); ++i) pmf.push_back(bvh.pmf(s.p, s.n, i));
    Rng rng(13, 14);
    const uint64_t n = 200000;
    std::vector<uint64_t> counts(lights.size(), 0);
    for (uint64_t k = 0; k < n; ++k) ++counts[bvh.pick(s.p, s.n, uniform53(rng)).light];
    std::string why;
    EXPECT_TRUE(discreteChi2Accepts(counts, pmf, n, sidakAlpha(0.01, int(points.size())), &why)) << why;
    // Power alone is a different distribution here: rejected.
    const PowerLightSelection power = makePowerLightSelection(summarizeLights(lights));
    std::vector<double> wrong;
    for (uint32_t i = 0; i < lights.size(); ++i) wrong.push_back(power.pmf(s.p, s.n, i));
    EXPECT_FALSE(discreteChi2Accepts(counts, wrong, n, 0.01));
  }
}

TEST(LightBvh, PrefersNearAndPowerfulLights) {
  std::vector<SphereLight> lights(3);
  lights[0].sphere = {Vec3(0, 1, 0), 0.1f};
  lights[1].sphere = {Vec3(20, 1, 0), 0.1f};
  lights[2].sphere = {Vec3(0, -3, 0), 0.1f};  // below the floor's horizon
  for (SphereLight& l : lights) l.radiance = Color3(1.f);
  const LightBvh bvh = makeLightBvh(summarizeLights(lights));
  const Vec3 p(0, 0, 0), up(0, 1, 0);
  EXPECT_GT(bvh.pmf(p, up, 0), 0.9);
  EXPECT_GT(bvh.pmf(p, up, 1), 0.0);
  EXPECT_EQ(bvh.pmf(p, up, 2), 0.0);
  EXPECT_GT(bvh.pmf(p, Vec3(0), 2), 0.0);  // no normal: no horizon
}

TEST(LightBvh, DegenerateInputsGiveNoNaN) {
  // Zero-power lights among others: never picked, pmf 0.
  auto lights = randomLights(20, 15);
  for (int i = 0; i < 20; i += 3) lights[size_t(i)].radiance = Color3(0.f);
  lights[4].sphere.radius = 0.f;
  {
    const LightBvh bvh = makeLightBvh(summarizeLights(lights));
    expectConsistentBvh(lights, bvh, 100, 16);
    for (const ShadingPointSample& s : shadingPoints(50, 17)) {
      for (int i = 0; i < 20; i += 3) EXPECT_EQ(bvh.pmf(s.p, s.n, uint32_t(i)), 0.0);
      EXPECT_EQ(bvh.pmf(s.p, s.n, 4), 0.0);
    }
  }
  // Every light dark: chosen by geometry alone, still a distribution.
  auto dark = randomLights(9, 18);
  for (SphereLight& l : dark) l.radiance = Color3(0.f);
  expectConsistentBvh(dark, makeLightBvh(summarizeLights(dark)), 100, 19);
  // Coincident lights (and one of radius 0 at the same centre).
  std::vector<SphereLight> same(12);
  for (size_t i = 0; i < same.size(); ++i) {
    same[i].sphere = {Vec3(1, 2, 3), i == 5 ? 0.f : 0.5f};
    same[i].radiance = Color3(float(i + 1));
  }
  const LightBvh coincident = makeLightBvh(summarizeLights(same));
  expectConsistentBvh(same, coincident, 100, 20);
  // Shading points inside a light's bounds, at its centre, and on its surface.
  for (const Vec3& p : {Vec3(1, 2, 3), Vec3(1.2f, 2, 3), Vec3(1, 2.5f, 3)}) {
    double sum = 0.0;
    for (uint32_t i = 0; i < same.size(); ++i) sum += coincident.pmf(p, Vec3(0, 1, 0), i);
    EXPECT_NEAR(sum, 1.0, 1e-12);
    const LightPick pick = coincident.pick(p, Vec3(0, 1, 0), 0.37);
    EXPECT_GT(pick.pmf, 0.0);
  }
  // No lights.
  const LightBvh empty = makeLightBvh(summarizeLights({}));
  EXPECT_EQ(empty.pick(Vec3(0), Vec3(0), 0.5).pmf, 0.0);
}

TEST(LightBvh, TenThousandLightsStayShallow) {
  const auto lights = randomLights(10000, 21, 20.f);
  const LightBvh bvh = makeLightBvh(summarizeLights(lights));
  int maxDepth = 0;
  for (uint32_t leaf : bvh.leafOf) {
    int depth = 0;
    for (uint32_t i = leaf; i != 0; i = bvh.nodes[i].parent) ++depth;
    maxDepth = std::max(maxDepth, depth);
  }
  EXPECT_LT(maxDepth, 40);
  expectConsistentBvh(lights, bvh, 5, 22);
}

}  // namespace
}  // namespace penumbra
