#include "core/integrators/direct_integrator.h"

#include <gtest/gtest.h>

#include <numbers>

#include "core/integrators/integrator_test_scene.h"

namespace penumbra {
namespace {

using test::addSphereLight;
using test::estimateOnTop;
using test::Moments;
using test::receiverScene;

// A sphere light of radius r, radiance L at distance d from x, fully above x's horizon at angle θ
// from the normal, gives irradiance E = π L sin²α cos θ (sin α = r / d); an albedo-1 diffuse
// receiver reflects Lr = E / π = L sin²α cos θ.
constexpr float kRadius = 0.5f, kRadiance = 3.f;
const Vec3 kLightCenter(0.6f, 0.f, 3.f);

double closedForm() {
  const double dx = kLightCenter.x, dz = kLightCenter.z - 1.0;
  const double d2 = dx * dx + dz * dz;
  return kRadiance * (double(kRadius) * kRadius / d2) * (dz / std::sqrt(d2));
}

Scene litScene() {
  Scene s = receiverScene();
  addSphereLight(s, kLightCenter, kRadius, kRadiance);
  s.geometry.build(AccelMode::BruteForce);
  return s;
}

template <Strategy kStrategy>
void expectClosedForm(int n) {
  Scene scene = litScene();
  Moments m = estimateOnTop(scene, DirectIntegrator<kStrategy>{1}, n, 11);
  EXPECT_EQ(m.bad, 0u);
  EXPECT_GT(m.standardError, 0.0);
  EXPECT_NEAR(m.mean, closedForm(), 4.0 * m.standardError + 1e-6) << "±" << m.standardError;
}

TEST(DirectIntegrator, SolidAngleSamplingMatchesTheClosedForm) {
  expectClosedForm<Strategy::DirectSolidAngle>(20000);
}

TEST(DirectIntegrator, AreaSamplingMatchesTheClosedForm) {
  expectClosedForm<Strategy::DirectArea>(20000);
}

TEST(DirectIntegrator, CosineHemisphereSamplingMatchesTheClosedForm) {
  expectClosedForm<Strategy::DirectCosineHemisphere>(200000);
}

TEST(DirectIntegrator, UniformHemisphereSamplingMatchesTheClosedForm) {
  expectClosedForm<Strategy::DirectUniformHemisphere>(200000);
}

// `simple` sees delta lights only: a point light of intensity I at height h over x gives
// Lr = albedo/π · I / h², deterministically, and an area light adds nothing.
TEST(DirectIntegrator, SimpleAddsPointLightsAndIgnoresAreaLights) {
  Scene scene = receiverScene();
  addSphereLight(scene, kLightCenter, kRadius, kRadiance);
  scene.pointLights.push_back(PointLight{Vec3(0.f, 0.f, 3.f), Color3(8.f)});
  scene.geometry.build(AccelMode::BruteForce);
  Moments m = estimateOnTop(scene, DirectIntegrator<Strategy::Simple>{1}, 16, 3);
  EXPECT_EQ(m.bad, 0u);
  EXPECT_NEAR(m.mean, 8.0 / (std::numbers::pi * 4.0), 1e-6);
  EXPECT_EQ(m.standardError, 0.0);
}

// The emitter itself: a camera ray that hits the light's front sees its radiance.
TEST(DirectIntegrator, ACameraRayOntoTheLightSeesItsRadiance) {
  Scene scene = litScene();
  Ray ray;
  ray.o = kLightCenter + Vec3(0.f, 0.f, 2.f);
  ray.d = Vec3(0.f, 0.f, -1.f);
  Sampler sampler(SamplerKind::Independent, 1, 1);
  sampler.startPixelSample(IVec2(0), 0);
  EXPECT_FLOAT_EQ(DirectIntegrator<Strategy::DirectSolidAngle>{1}.Li(scene, ray, sampler).x, kRadiance);
}

}  // namespace
}  // namespace penumbra
