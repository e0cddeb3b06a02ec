// The error rate of whole renders with each sampler, on the assignment's sphere scene with
// solid-angle light sampling: floor pixels whose every filter sample sees the whole light, where the
// closed-form reference is exact; log MSE against log spp is fitted over 4..256 spp.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/analysis/analysis_test_support.h"
#include "core/analysis/error_metrics.h"
#include "core/analysis/reference.h"
#include "core/render/camera.h"
#include "core/render/engine.h"

namespace penumbra {
namespace {

// Pixels whose 9 x 9 grid of offsets over the filter's support all hit the floor (z = -1) and see
// all of 64 points of the light's visible side: the light is unoccluded over the whole footprint.
std::vector<int> unoccludedFloorPixels(const LoadedScene& s) {
  PerspectiveCamera camera(s.settings.camera);
  const float radius = s.settings.filter.radius;  // every sample lands within it
  const SphereLight& light = s.scene->sphereLights.at(0);
  std::vector<Vec3> onLight;
  for (int i = 0; i < 64; ++i) {  // a Fibonacci sphere of directions
    float z = 1.f - (i + 0.5f) / 32.f, r = std::sqrt(std::max(0.f, 1.f - z * z)), phi = 2.39996323f * i;
    onLight.push_back(light.sphere.center +
                      light.sphere.radius * Vec3(r * std::cos(phi), r * std::sin(phi), z));
  }
  std::vector<int> pixels;
  for (int y = 0; y < camera.height(); ++y)
    for (int x = 0; x < camera.width(); ++x) {
      bool ok = true;
      for (int j = 0; j < 81 && ok; ++j) {
        Vec2 offset = radius * Vec2(j % 9 / 4.f - 1.f, j / 9 / 4.f - 1.f);
        SurfaceHit hit;
        Ray ray = camera.generateRay(Vec2(x + 0.5f + offset.x, y + 0.5f + offset.y));
        if (!s.scene->geometry.intersect(ray, hit) || std::fabs(hit.p.z + 1.f) > 1e-3f || hit.ng.z < 0.99f) {
          ok = false;
          break;
        }
        for (const Vec3& p : onLight) {
          Vec3 d = p - hit.p;
          if (glm::dot(p - light.sphere.center, -d) <= 0.f) continue;  // the light's far side
          float dist = glm::length(d);
          Ray shadow{hit.p + Vec3(0, 0, 1e-4f), d / dist, 0.f, dist * 0.999f};
          if (s.scene->geometry.occluded(shadow)) {
            ok = false;
            break;
          }
        }
      }
      if (ok) pixels.push_back(y * camera.width() + x);
    }
  return pixels;
}

double maskedMse(const Image& estimate, const Image& truth, const std::vector<int>& pixels) {
  double sum = 0;
  for (int i : pixels) {
    Color3 e = estimate.at(i % estimate.width, i / estimate.width),
           t = truth.at(i % truth.width, i / truth.width);
    double d = (double(e.x) - t.x + double(e.y) - t.y + double(e.z) - t.z) / 3.0;
    sum += d * d;
  }
  return sum / pixels.size();
}

// Fitted slope of log MSE against log spp (spp 4, 16, 64, 256; MSE averaged over `seeds` renders).
double renderMseSlope(const std::string& sampler, int seeds, int* pixelCount = nullptr) {
  LoadedScene s = loadScene(test::sphereScene(), {{"camera.width", "40"},
                                                  {"camera.height", "40"},
                                                  {"integrator.measure", "solid-angle"},
                                                  {"sampler.type", sampler}});
  Reference truth = closedFormReference(s, 64);
  std::vector<int> pixels = unoccludedFloorPixels(s);
  if (pixelCount) *pixelCount = static_cast<int>(pixels.size());
  std::vector<double> sppValues, mseValues;
  for (uint32_t spp : {4u, 16u, 64u, 256u}) {
    double mse = 0;
    for (int seed = 0; seed < seeds; ++seed) {
      RenderSettings settings = s.settings;
      settings.seed = static_cast<uint64_t>(seed) + 1;
      const RenderLimits limits{spp, 0};  // the job fits zsobol's nets to spp
      Engine engine;
      engine.start(std::make_shared<const RenderJob>(s.scene, settings, limits), limits, 2);
      engine.wait();
      mse += maskedMse(engine.film().mean(spp), truth.mean, pixels) / seeds;
    }
    sppValues.push_back(double(spp));
    mseValues.push_back(mse);
    std::printf("  %s %u spp: MSE %.3e\n", sampler.c_str(), spp, mse);
  }
  return logLogSlope(sppValues, mseValues);
}

TEST(SamplerRenderRate, IndependentSamplingConvergesAsOneOverN) {
  int pixels = 0;
  double slope = renderMseSlope("independent", 2, &pixels);
  std::printf("independent: %d unoccluded floor pixels, slope of log MSE against log spp %.2f\n", pixels,
              slope);
  EXPECT_GT(pixels, 200);
  EXPECT_NEAR(slope, -1.0, 0.15);
}

TEST(SamplerRenderRate, SobolSamplersConvergeFaster) {
  for (const char* sampler : {"sobol", "zsobol"}) {
    double slope = renderMseSlope(sampler, 2);
    std::printf("%s: slope of log MSE against log spp %.2f\n", sampler, slope);
    EXPECT_LE(slope, -1.4) << sampler;
  }
}

}  // namespace
}  // namespace penumbra
