#include "core/integrators/mis_light_share.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/integrators/integrator_test_support.h"

namespace penumbra {
namespace {

using test::Estimate;

const Vec3 kX(0.31f, 0.17f, 0.f);

// Mean ± standard error of each channel of n camera samples along one ray.
struct ChannelEstimate {
  Estimate channel[3];
};

template <class Integrator>
ChannelEstimate estimateChannels(const Scene& scene, const Integrator& integrator, const Ray& ray, int n,
                                 uint64_t seed) {
  Sampler sampler(SamplerKind::Independent, 1, seed);
  double sum[3] = {}, sumSq[3] = {};
  ChannelEstimate e;
  for (int i = 0; i < n; ++i) {
    sampler.startPixelSample(IVec2(7, 11), uint32_t(i));
    const Color3 L = integrator.Li(scene, ray, sampler);
    for (int c = 0; c < 3; ++c) {
      if (!(L[c] >= 0.f) || !std::isfinite(L[c])) {
        ++e.channel[c].bad;
        continue;
      }
      sum[c] += L[c];
      sumSq[c] += double(L[c]) * L[c];
    }
  }
  for (int c = 0; c < 3; ++c) {
    const double mean = sum[c] / n;
    e.channel[c].mean = mean;
    e.channel[c].standardError = std::sqrt(std::max(0.0, sumSq[c] / n - mean * mean) / (n - 1.0));
  }
  return e;
}

// Two lights (a large one near the plane and a small one), an occluder and a point light, so every
// channel carries something.
std::unique_ptr<Scene> mixedScene() {
  auto scene = test::planeScene({{kX + Vec3(1.2f, 0.f, 0.4f), 0.8f, 3.f},
                                 {kX + Vec3(-0.3f, 0.4f, 1.5f), 0.05f, 400.f},
                                 {kX + Vec3(0.5f, 0.1f, 0.2f), 0.1f, 0.f}});
  scene->pointLights.push_back(PointLight{kX + Vec3(0.f, -1.f, 1.f), Color3(2.f, 1.f, 0.5f)});
  return scene;
}

// Per camera sample, R + G + B of the split equals the luminance of the MIS estimate (same stream),
// and every channel is finite and >= 0; on the plane and on a light seen directly (whose whole estimate
// is in B).
template <LightMeasure kMeasure, MisHeuristic kHeuristic>
void expectChannelsAddUp(const Scene& scene, int nL, int nB) {
  const MisIntegrator<kMeasure, kHeuristic> mis{nL, nB};
  const MisLightShareIntegrator<kMeasure, kHeuristic> share{mis};
  const Ray onPlane = test::shallowRayOnto(kX);
  Ray onLight;
  onLight.o = kX + Vec3(1.2f, -3.f, 0.4f);
  onLight.d = Vec3(0.f, 1.f, 0.f);
  int withLight = 0, withBsdf = 0, differing = 0, bad = 0, lightShared = 0;
  const Ray rays[] = {onPlane, onLight};
  for (int r = 0; r < 2; ++r) {
    const Ray& ray = rays[r];
    Sampler a(SamplerKind::Independent, 1, 5), b(SamplerKind::Independent, 1, 5);
    for (uint32_t i = 0; i < 4000; ++i) {
      a.startPixelSample(IVec2(1, 2), i);
      b.startPixelSample(IVec2(1, 2), i);
      const float expected = luminance(mis.Li(scene, ray, a));
      const Color3 parts = share.Li(scene, ray, b);
      bad += !(isValidRadiance(parts));
      withLight += parts.x > 0.f;
      withBsdf += parts.y > 0.f;
      lightShared += r == 1 && (parts.x != 0.f || parts.y != 0.f);  // a light: all in B
      const float sum = parts.x + parts.y + parts.z;
      differing += !(std::fabs(sum - expected) <= 1e-6f * std::max(1.f, expected));
    }
  }
  EXPECT_EQ(bad, 0);
  EXPECT_EQ(lightShared, 0);
  EXPECT_EQ(differing, 0) << nL << "+" << nB;
  EXPECT_GT(withLight, nL > 0 ? 1000 : -1) << nL << "+" << nB;
  EXPECT_EQ(withLight > 0, nL > 0) << nL << "+" << nB;
  EXPECT_EQ(withBsdf > 0, nB > 0) << nL << "+" << nB;
}

TEST(MisLightShare, ChannelsAddUpToTheLuminanceOfTheMisEstimate) {
  auto scene = mixedScene();
  for (auto [nL, nB] : {std::pair{1, 1}, std::pair{2, 3}, std::pair{1, 0}, std::pair{0, 2}}) {
    expectChannelsAddUp<LightMeasure::SolidAngle, MisHeuristic::Power>(*scene, nL, nB);
    expectChannelsAddUp<LightMeasure::SolidAngle, MisHeuristic::Balance>(*scene, nL, nB);
    expectChannelsAddUp<LightMeasure::Area, MisHeuristic::Power>(*scene, nL, nB);
    expectChannelsAddUp<LightMeasure::Area, MisHeuristic::Balance>(*scene, nL, nB);
    expectChannelsAddUp<LightMeasure::ProjectedSolidAngle, MisHeuristic::Power>(*scene, nL, nB);
    expectChannelsAddUp<LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance>(*scene, nL, nB);
  }
}

// One light of half-angle α straight above the shading point (albedo 1, radiance Le). Both parts are
// (Le/π) ∫cone cos θ w_t(θ) dω with the weights of the two techniques' densities.
struct OverheadLight {
  double sinAlpha, Le;
  double cosAlpha() const { return std::sqrt(1.0 - sinAlpha * sinAlpha); }

  // Projected solid angle with its light: pL = cos θ / (π sin²α) and pB = cos θ / π are proportional,
  // so the weights are constants, w_L = 1 / (1 + (nB/nL sin²α)^β) (β = 1 balance, 2 power), and the
  // light part is w_L times the irradiance (Le/π) π sin²α.
  double psaLightPart(int nL, int nB, bool power) const {
    const double r = double(nB) / nL * sinAlpha * sinAlpha;
    return Le * sinAlpha * sinAlpha / (1.0 + (power ? r * r : r));
  }
  // Solid angle: pL = 1 / (2π(1 − cos α)), pB = cos θ / π; the θ integral by Simpson's rule.
  double solidAngleLightPart(int nL, int nB, bool power) const {
    const double alpha = std::asin(sinAlpha), pL = 1.0 / (2.0 * kPiD * (1.0 - cosAlpha()));
    const int steps = 20000;
    double sum = 0;
    for (int i = 0; i <= steps; ++i) {
      const double t = alpha * i / steps, pB = std::cos(t) / kPiD;
      const double a = nL * pL, b = nB * pB;
      const double w = power ? a * a / (a * a + b * b) : a / (a + b);
      const double f = std::cos(t) * std::sin(t) * w * 2.0 * kPiD;
      sum += f * (i == 0 || i == steps ? 1 : i % 2 ? 4 : 2);
    }
    return Le / kPiD * sum * alpha / steps / 3.0;
  }
  double irradiancePart() const { return Le * sinAlpha * sinAlpha; }  // (Le/π) π sin²α
};

template <LightMeasure kMeasure, MisHeuristic kHeuristic>
void expectShare(const Scene& scene, const Ray& ray, double lightTruth, double total, int nL, int nB,
                 const char* what) {
  const MisLightShareIntegrator<kMeasure, kHeuristic> share{{nL, nB}};
  const ChannelEstimate e = estimateChannels(scene, share, ray, 60000, 3 + nL + 5 * nB);
  const Estimate &light = e.channel[0], &bsdf = e.channel[1];
  EXPECT_EQ(light.bad + bsdf.bad, 0u) << what;
  EXPECT_NEAR(light.mean, lightTruth, 4 * light.standardError + 1e-5 * total)
      << what << " " << nL << "+" << nB;
  EXPECT_NEAR(bsdf.mean, total - lightTruth, 4 * bsdf.standardError + 1e-5 * total)
      << what << " " << nL << "+" << nB;
  const float s = lightShare(Color3(float(light.mean), float(bsdf.mean), 0.f));
  EXPECT_GE(s, 0.f);
  EXPECT_LE(s, 1.f);
}

TEST(MisLightShare, MatchesTheClosedFormShareOfAnOverheadLight) {
  auto scene = test::planeScene({{kX + Vec3(0.f, 0.f, 2.f), 0.8f, 5.f}});
  const Ray ray = test::shallowRayOnto(kX);
  const OverheadLight light{0.4, 5.0};
  const double total = light.irradiancePart() / kPiD * kPiD;  // albedo 1: Lr = E / π, E = Le π sin²α
  for (auto [nL, nB] : {std::pair{1, 1}, std::pair{1, 3}, std::pair{2, 1}}) {
    expectShare<LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance>(
        *scene, ray, light.psaLightPart(nL, nB, false), total, nL, nB, "psa balance");
    expectShare<LightMeasure::ProjectedSolidAngle, MisHeuristic::Power>(
        *scene, ray, light.psaLightPart(nL, nB, true), total, nL, nB, "psa power");
    expectShare<LightMeasure::SolidAngle, MisHeuristic::Balance>(
        *scene, ray, light.solidAngleLightPart(nL, nB, false), total, nL, nB, "solid-angle balance");
    expectShare<LightMeasure::SolidAngle, MisHeuristic::Power>(
        *scene, ray, light.solidAngleLightPart(nL, nB, true), total, nL, nB, "solid-angle power");
  }
}

// No cosine samples: everything is light sampling (share 1); no light samples: share 0.
TEST(MisLightShare, AZeroCountGivesShareOneOrZero) {
  auto scene = mixedScene();
  const Ray ray = test::shallowRayOnto(kX);
  const MisLightShareIntegrator<LightMeasure::Area, MisHeuristic::Power> lightOnly{{2, 0}};
  const MisLightShareIntegrator<LightMeasure::Area, MisHeuristic::Power> bsdfOnly{{0, 2}};
  const ChannelEstimate a = estimateChannels(*scene, lightOnly, ray, 4000, 1);
  const ChannelEstimate b = estimateChannels(*scene, bsdfOnly, ray, 4000, 1);
  EXPECT_EQ(a.channel[1].mean, 0.0);
  EXPECT_EQ(b.channel[0].mean, 0.0);
  EXPECT_EQ(lightShare(Color3(float(a.channel[0].mean), float(a.channel[1].mean), 0.f)), 1.f);
  EXPECT_EQ(lightShare(Color3(float(b.channel[0].mean), float(b.channel[1].mean), 0.f)), 0.f);
  EXPECT_LT(lightShare(Color3(0.f, 0.f, 1.f)), 0.f);  // no area light: no share
  EXPECT_LT(lightShare(Color3(INFINITY, 0.f, 0.f)), 0.f);
}

}  // namespace
}  // namespace penumbra
