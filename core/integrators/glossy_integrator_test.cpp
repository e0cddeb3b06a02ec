// Glossy surfaces through the integrators: every estimator (uniform and cosine hemisphere, BSDF
// sampling, the three light measures, MIS of each with both heuristics, a light selection) unbiased on
// a glossy point under a sphere light against a quadrature of ∫ Le f cos θ dω over the light's cone,
// with an independent and a low-discrepancy sampler; on a diffuse surface BSDF sampling is the cosine
// warp sample for sample; a light sample weighted with a wrong BSDF density fails the same bound.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/integrators/integrator_test_support.h"
#include "core/materials/bsdf_albedo.h"

namespace penumbra {
namespace {

using test::Estimate;

constexpr Vec3 kLightCenter(0.45f, 0.1f, 1.2f);
constexpr float kLightRadius = 0.3f, kRadiance = 4.f;

struct GlossyCase {
  std::string name;
  Bsdf bsdf;
  Vec3 eye;  // the camera ray runs from here to the origin
};

std::vector<GlossyCase> glossyCases() {
  const Vec3 mirror(-0.45f, -0.1f, 1.2f);  // the light's centre mirrored: the highlight's peak
  const Vec3 off(-1.2f, 0.4f, 0.9f);       // the highlight's tail
  return {
      {"microfacet a0.2 kd0.3 mirror", makeMicrofacet(Color3(0.3f), 0.2f, 1.5046f, 1.000277f), mirror},
      {"microfacet a0.05 kd0 mirror", makeMicrofacet(Color3(0.f), 0.05f, 1.5046f, 1.000277f), mirror},
      {"roughconductor beckmann a0.1 mirror",
       makeRoughConductor(MicrofacetDistribution::Beckmann, 0.1f, Color3(1.f)), mirror},
      {"roughconductor ggx a0.3 off", makeRoughConductor(MicrofacetDistribution::Ggx, 0.3f, Color3(0.9f)),
       off},
      {"roughconductor ggx a0.05 mirror", makeRoughConductor(MicrofacetDistribution::Ggx, 0.05f, Color3(1.f)),
       mirror},
      {"roughconductor beckmann a1 off",
       makeRoughConductor(MicrofacetDistribution::Beckmann, 1.f, Color3(1.f)), off},
  };
}

struct GlossyScene {
  std::unique_ptr<Scene> scene;
  Ray ray;
  double truth = 0;
};

GlossyScene glossyScene(const GlossyCase& c) {
  GlossyScene out;
  out.scene = test::planeScene(10.f);
  out.scene->materials[0].bsdf = c.bsdf;
  test::addSphere(*out.scene, kLightCenter, kLightRadius, Color3(kRadiance));
  test::finish(*out.scene);
  out.ray.o = c.eye;
  out.ray.d = glm::normalize(-c.eye);
  // The shading frame at the hit is Frame(+z), the identity up to the basis's signs: express wo in it.
  const Frame frame(Vec3(0.f, 0.f, 1.f));
  const double d = glm::length(glm::dvec3(kLightCenter)), sinMax = kLightRadius / d;
  out.truth = kRadiance * coneReflectance(c.bsdf, frame.toLocal(glm::normalize(c.eye)),
                                          glm::dvec3(kLightCenter) / d, std::sqrt(1 - sinMax * sinMax));
  return out;
}

template <IntegratorDesc D>
Estimate estimate(const GlossyScene& s, SamplerKind kind, int n = 1 << 15) {
  return test::estimateAlong(*s.scene, test::integratorOf<D>(1), s.ray, n, 9, kind);
}

void expectUnbiased(const Estimate& e, double truth, const std::string& what) {
  if (std::getenv("PENUMBRA_VERBOSE"))
    std::printf("%-70s truth %.7g mean %.7g SE %.3g\n", what.c_str(), truth, e.mean, e.standardError);
  EXPECT_EQ(e.bad, 0u) << what;
  // 4.5 SE: Šidák over the ~150 estimates here at a 1 % family-wise level needs 3.9; plus the
  // quadrature's error.
  EXPECT_NEAR(e.mean, truth, 4.5 * e.standardError + 2e-4 * truth) << what;
}

// A strategy's name in messages (the strategy tables live in a higher layer).
std::string describe(const IntegratorDesc& d) {
  const char* estimators[] = {"hemisphere", "bsdf", "light", "mis"};
  return std::string(estimators[int(d.estimator)]) + " warp " + std::to_string(int(d.warp)) + " measure " +
         std::to_string(int(d.lightMeasure)) + " selection " + std::to_string(int(d.lightSelection)) +
         " heuristic " + std::to_string(int(d.heuristic));
}

template <IntegratorDesc D>
void check(const GlossyScene& s, const GlossyCase& c, SamplerKind kind) {
  expectUnbiased(estimate<D>(s, kind), s.truth,
                 c.name + " " + describe(D) + " " + std::string(samplerKindName(kind)));
}

TEST(GlossyIntegrators, EveryEstimatorIsUnbiasedOnGlossySurfaces) {
  for (const GlossyCase& c : glossyCases()) {
    const GlossyScene s = glossyScene(c);
    ASSERT_GT(s.truth, 0.0) << c.name;
    for (SamplerKind kind : {SamplerKind::Independent, SamplerKind::ZSobol}) {
      check<directByHemisphere(HemisphereWarp::Uniform)>(s, c, kind);
      check<directByHemisphere(HemisphereWarp::Cosine)>(s, c, kind);
      check<directByBsdf()>(s, c, kind);
      check<directByLight(LightMeasure::Area)>(s, c, kind);
      check<directByLight(LightMeasure::SolidAngle)>(s, c, kind);
      check<directByLight(LightMeasure::ProjectedSolidAngle)>(s, c, kind);
      check<directByLight(LightMeasure::SolidAngle, LightSelection::Bvh)>(s, c, kind);
      check<directByMis(LightMeasure::Area, MisHeuristic::Power)>(s, c, kind);
      check<directByMis(LightMeasure::SolidAngle, MisHeuristic::Power)>(s, c, kind);
      check<directByMis(LightMeasure::SolidAngle, MisHeuristic::Balance)>(s, c, kind);
      check<directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Power)>(s, c, kind);
    }
  }
}

// MIS with the light samples' weights computed from the cosine density instead of the BSDF's: the
// weights of a light direction and a BSDF direction no longer add to 1, and the bound rejects it.
struct WrongDensityMis {
  Color3 Li(const Scene& scene, const Ray& ray, Sampler& sampler) const {
    return directRadiance<true>(scene, ray, [&](const ShadingPoint& sp, const auto& reflection) {
      const auto lightPart = everyLightIrradiance<LightMeasure::SolidAngle>(
          scene, sp, reflection, sampler, 1, [&](const LightSample& s, float cosTheta) {
            return misWeight<MisHeuristic::Balance>(s.pdf, cosTheta * kInvPi);
          });
      const auto bsdfPart = surfaceSampledRadiance(
          scene, sp, reflection, sampler, 1,
          [&](const auto& light, const SurfaceHit& hit, const Vec3& w, float pdf) {
            using Light = std::decay_t<decltype(light)>;
            return misWeight<MisHeuristic::Balance>(
                pdf, LightTechnique<LightMeasure::SolidAngle, Light>(light, sp).pdf(w, hit.p, hit.ng));
          });
      return lightPart + bsdfPart;
    });
  }
};

TEST(GlossyIntegrators, AWrongDensityInTheWeightsFails) {
  const GlossyCase c = glossyCases()[2];  // a sharp Beckmann conductor at its highlight
  const GlossyScene s = glossyScene(c);
  const Estimate e = test::estimateAlong(*s.scene, WrongDensityMis{}, s.ray, 1 << 15, 9);
  EXPECT_GT(std::abs(e.mean - s.truth), 10 * e.standardError)
      << "truth " << s.truth << " mean " << e.mean << " SE " << e.standardError;
}

TEST(GlossyIntegrators, BsdfSamplingOfADiffuseSurfaceIsTheCosineWarp) {
  auto scene = test::planeScene({{Vec3(0.3f, 0.f, 1.f), 0.4f, 3.f}, {Vec3(-2.f, 1.f, 0.5f), 0.2f, 30.f}});
  const auto bsdf = test::integratorOf<directByBsdf()>(2);
  const auto cosine = test::integratorOf<directByHemisphere(HemisphereWarp::Cosine)>(2);
  for (SamplerKind kind : {SamplerKind::Independent, SamplerKind::ZSobol}) {
    Sampler a(kind, 256, 4), b(kind, 256, 4);
    for (uint32_t i = 0; i < 256; ++i) {
      a.startPixelSample(IVec2(3, 5), i);
      b.startPixelSample(IVec2(3, 5), i);
      const Ray ray = test::rayDownOnto(0.01f * float(i % 16), 0.02f * float(i / 16));
      const Color3 x = bsdf.Li(*scene, ray, a), y = cosine.Li(*scene, ray, b);
      ASSERT_EQ(x.x, y.x);
      ASSERT_EQ(x.y, y.y);
      ASSERT_EQ(x.z, y.z);
    }
  }
}

}  // namespace
}  // namespace penumbra
