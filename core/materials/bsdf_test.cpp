// The reflection models against their published formulas, written again here in double from the
// papers' text (Walter et al. 2007's D and G1, Fresnel's equations), at fixed directions; reciprocity;
// directional albedo at most 1 for every roughness; each pdf integrating to at most 1 (the rest is
// the mass of draws reflected below the surface); χ² of every sampler against its pdf, with a
// deliberately wrong density and a deliberately wrong sampler rejected; no NaN, Inf or negative value
// at the extremes.
#include "core/materials/bsdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/materials/bsdf_albedo.h"
#include "core/materials/bsdf_warp.h"
#include "core/materials/microfacet_distribution.h"
#include "core/math/float_util.h"
#include "core/sampling/chi2.h"
#include "core/sampling/rng.h"

namespace penumbra {
namespace {

// ---- the formulas, in double --------------------------------------------------------------------

double tan2Of(const DVec3& v) {
  return (v.x * v.x + v.y * v.y) / (v.z * v.z);
}

double beckmannD(const DVec3& h, double a) {
  const double c = h.z;
  return std::exp(-tan2Of(h) / (a * a)) / (kPiD * a * a * c * c * c * c);
}

double ggxD(const DVec3& h, double a) {
  const double c = h.z, t = tan2Of(h) / (a * a);
  return 1.0 / (kPiD * a * a * c * c * c * c * (1 + t) * (1 + t));
}

double beckmannG1(const DVec3& v, const DVec3& h, double a) {
  if (glm::dot(v, h) * v.z <= 0) return 0;
  const double b = 1.0 / (a * std::sqrt(tan2Of(v)));
  return b < 1.6 ? (3.535 * b + 2.181 * b * b) / (1 + 2.276 * b + 2.577 * b * b) : 1.0;
}

double ggxG1(const DVec3& v, const DVec3& h, double a) {
  if (glm::dot(v, h) * v.z <= 0) return 0;
  return 2.0 / (1 + std::sqrt(1 + a * a * tan2Of(v)));
}

double fresnel(double cosI, double n1, double n2) {
  const double sinT = n1 / n2 * std::sqrt(std::max(0.0, 1 - cosI * cosI));
  if (sinT >= 1) return 1;
  const double cosT = std::sqrt(1 - sinT * sinT);
  const double rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
  const double rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
  return 0.5 * (rs * rs + rp * rp);
}

// f of the formulas for the first channel.
double referenceF(const Bsdf& b, const DVec3& wo, const DVec3& wi) {
  if (wo.z <= 0 || wi.z <= 0) return 0;
  const DVec3 h = glm::normalize(wo + wi);
  const double a = b.alpha;
  if (b.type == BsdfType::Diffuse) return b.albedo.x / kPiD;
  if (b.type == BsdfType::Microfacet) {
    const double kd = b.albedo.x, ks = 1 - std::max({b.albedo.x, b.albedo.y, b.albedo.z});
    return kd / kPiD + ks * beckmannD(h, a) * fresnel(glm::dot(h, wi), b.extIOR, b.intIOR) *
                           beckmannG1(wi, h, a) * beckmannG1(wo, h, a) / (4 * wi.z * wo.z);
  }
  const bool ggx = b.distribution == MicrofacetDistribution::Ggx;
  const double D = ggx ? ggxD(h, a) : beckmannD(h, a);
  const double G = ggx ? ggxG1(wi, h, a) * ggxG1(wo, h, a) : beckmannG1(wi, h, a) * beckmannG1(wo, h, a);
  return b.specularReflectance.x * D * G / (4 * wi.z * wo.z);
}

DVec3 direction(double thetaDeg, double phiDeg) {
  const double t = thetaDeg * kPiD / 180, p = phiDeg * kPiD / 180;
  return DVec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
}

std::vector<Bsdf> models() {
  std::vector<Bsdf> out = {makeDiffuse(Color3(0.7f))};
  for (float a : {0.01f, 0.1f, 0.3f, 1.f}) {
    out.push_back(makeMicrofacet(Color3(0.3f), a, 1.5046f, 1.000277f));
    out.push_back(makeMicrofacet(Color3(0.f), a, 1.5046f, 1.000277f));
    out.push_back(makeRoughConductor(MicrofacetDistribution::Beckmann, a, Color3(0.9f)));
    out.push_back(makeRoughConductor(MicrofacetDistribution::Ggx, a, Color3(0.9f)));
  }
  return out;
}

std::string nameOf(const Bsdf& b) {
  std::string type = b.type == BsdfType::Diffuse      ? "diffuse"
                     : b.type == BsdfType::Microfacet ? "microfacet kd " + std::to_string(b.albedo.x)
                     : b.distribution == MicrofacetDistribution::Ggx ? "roughconductor ggx"
                                                                     : "roughconductor beckmann";
  return type + " alpha " + std::to_string(b.alpha);
}

TEST(Bsdf, EvaluationMatchesThePublishedFormulas) {
  int checked = 0;
  for (const Bsdf& b : models())
    for (double to : {0.0, 20.0, 50.0, 80.0, 89.0})
      for (double ti : {0.0, 15.0, 45.0, 70.0, 88.0})
        for (double dphi : {180.0, 150.0, 90.0, 10.0}) {
          // The directions as the float code receives them (the formulas' exp would amplify their rounding).
          const DVec3 wo(Vec3(direction(to, 0))), wi(Vec3(direction(ti, dphi)));
          const double want = referenceF(b, wo, wi);
          const double got = evalBsdf(b, Vec3(wo), Vec3(wi)).x;
          // Float evaluation: a few ulps of each factor, and exp(-tan²/α²) amplifies the argument's
          // rounding by tan²/α² (up to ~87 where D is still above 0).
          const double e = tan2Of(glm::normalize(wo + wi)) / (b.alpha * b.alpha);
          const double tol = 2e-6 * (4 + std::min(e, 90.0)) * want + 1e-30;
          if (want < 1e-30) {
            EXPECT_LE(got, 1e-30) << nameOf(b) << " wo " << to << " wi " << ti << "," << dphi;
            continue;
          }
          EXPECT_NEAR(got, want, tol) << nameOf(b) << " wo " << to << " wi " << ti << "," << dphi;
          ++checked;
        }
  EXPECT_GT(checked, 1000);
}

TEST(Bsdf, EvaluationIsZeroUnlessBothDirectionsAreAbove) {
  for (const Bsdf& b : models()) {
    EXPECT_EQ(evalBsdf(b, Vec3(direction(30, 0)), Vec3(0.f, 0.6f, -0.8f)), Color3(0.f)) << nameOf(b);
    EXPECT_EQ(evalBsdf(b, Vec3(0.f, 0.6f, -0.8f), Vec3(direction(30, 0))), Color3(0.f)) << nameOf(b);
    EXPECT_EQ(evalBsdf(b, Vec3(1.f, 0.f, 0.f), Vec3(direction(30, 0))), Color3(0.f)) << nameOf(b);
    EXPECT_EQ(pdfBsdf(b, Vec3(direction(30, 0)), Vec3(0.f, 0.6f, -0.8f)), 0.f) << nameOf(b);
  }
}

TEST(Bsdf, IsReciprocal) {
  Rng rng(7, 3);
  for (const Bsdf& b : models())
    for (int i = 0; i < 2000; ++i) {
      const Vec3 wo = Warp::squareToUniformHemisphere(Vec2(rng.nextFloat(), rng.nextFloat()));
      const Vec3 wi = Warp::squareToUniformHemisphere(Vec2(rng.nextFloat(), rng.nextFloat()));
      const float a = evalBsdf(b, wo, wi).x, c = evalBsdf(b, wi, wo).x;
      // 1e-4: h·wi and h·wo, and the products, round differently in the two orders (and with FMA).
      ASSERT_NEAR(a, c, 1e-4f * std::max(a, c) + 1e-30f) << nameOf(b);
    }
}

TEST(Bsdf, DirectionalAlbedoIsAtMostOneForEveryRoughness) {
  for (float alpha : {1e-3f, 0.01f, 0.1f, 0.3f, 1.f, 3.f})
    for (double theta : {0.0, 45.0, 80.0, 89.0}) {
      const Vec3 wo(direction(theta, 0));
      for (const Bsdf& b : {makeMicrofacet(Color3(0.f), alpha, 1.5046f, 1.000277f),
                            makeRoughConductor(MicrofacetDistribution::Beckmann, alpha, Color3(1.f)),
                            makeRoughConductor(MicrofacetDistribution::Ggx, alpha, Color3(1.f))}) {
        const double albedo = directionalAlbedo(b, wo);
        EXPECT_LE(albedo, 1.0 + 2e-3) << nameOf(b) << " at " << theta << " deg";
        EXPECT_GT(albedo, 0.0) << nameOf(b) << " at " << theta << " deg";
        // A near-mirror conductor reflects (almost) everything at normal incidence.
        if (theta == 0.0 && alpha <= 0.01f && b.type == BsdfType::RoughConductor)
          EXPECT_NEAR(albedo, 1.0, 0.02) << nameOf(b);
      }
    }
  // microfacet: the diffuse part adds kd exactly; ks = 1 - max(kd) keeps the sum at most 1.
  const Bsdf m = makeMicrofacet(Color3(0.6f), 0.2f, 1.5046f, 1.000277f);
  const Vec3 wo(direction(30, 0));
  EXPECT_LE(directionalAlbedo(m, wo), 1.0);
  EXPECT_GT(directionalAlbedo(m, wo), 0.6);
}

// Each density integrates to at most 1 over the hemisphere, and to 1 minus the mass of the draws the
// sampler rejects (measured by drawing).
TEST(Bsdf, EachPdfIntegratesToOneMinusTheRejectedDraws) {
  for (float alpha : {1e-3f, 0.05f, 0.3f, 1.f})
    for (float theta : {0.f, 60.f, 85.f})
      for (const Bsdf& b : {makeMicrofacet(Color3(0.f), alpha, 1.5046f, 1.000277f),
                            makeRoughConductor(MicrofacetDistribution::Beckmann, alpha, Color3(1.f)),
                            makeRoughConductor(MicrofacetDistribution::Ggx, alpha, Color3(1.f))}) {
        BsdfWarp w{b, theta};
        const double mass = sampledMass(b, w.wo());
        Rng rng(11, 5);
        const int n = 200000;
        int rejected = 0;
        for (int i = 0; i < n; ++i) rejected += w.sample(Vec2(rng.nextFloat(), rng.nextFloat())) == Vec3(0.f);
        const double p = double(rejected) / n, se = std::sqrt(std::max(p * (1 - p), 1.0 / n) / n);
        EXPECT_LE(mass, 1.0 + 1e-3) << nameOf(b) << " at " << theta;
        EXPECT_NEAR(1.0 - mass, p, 5 * se + 2e-3) << nameOf(b) << " at " << theta;
      }
}

// ---- χ² -------------------------------------------------------------------------------------------

struct Chi2Case {
  BsdfWarp warp;
  std::string name;
};

std::vector<Chi2Case> chi2Cases() {
  std::vector<Chi2Case> out;
  for (float theta : {0.f, 40.f, 75.f, 89.f})
    for (float alpha : {0.03f, 0.2f, 0.7f}) {
      const std::string at = " alpha " + std::to_string(alpha) + " at " + std::to_string(theta);
      out.push_back(
          {{makeMicrofacet(Color3(0.4f), alpha, 1.5046f, 1.000277f), theta}, "microfacet kd 0.4" + at});
      out.push_back(
          {{makeMicrofacet(Color3(0.f), alpha, 1.5046f, 1.000277f), theta}, "microfacet kd 0" + at});
      out.push_back({{makeRoughConductor(MicrofacetDistribution::Beckmann, alpha, Color3(1.f)), theta},
                     "beckmann" + at});
      out.push_back(
          {{makeRoughConductor(MicrofacetDistribution::Ggx, alpha, Color3(1.f)), theta}, "ggx" + at});
    }
  return out;
}

Chi2Options bsdfChi2Options(int tests) {
  Chi2Options opt;
  opt.sampleCount = 400000;
  opt.resolution = 40;
  opt.testCount = tests;
  opt.rejectedDraws = true;
  return opt;
}

TEST(BsdfChi2, EverySamplerMatchesItsPdf) {
  const std::vector<Chi2Case> cases = chi2Cases();
  for (const Chi2Case& c : cases) {
    const Chi2Result r = chi2Test(bsdfChi2Domain(), bsdfSampleFunction(c.warp), bsdfPdfFunction(c.warp),
                                  bsdfChi2Options(int(cases.size())));
    EXPECT_TRUE(r.accepted) << c.name << ": " << r.message << " (chi2 " << r.chi2 << ", dof " << r.dof << ")";
    EXPECT_EQ(r.invalidSamples, 0u) << c.name;
  }
}

TEST(BsdfChi2, AWrongPdfIsRejected) {
  const std::vector<Chi2Case> cases = chi2Cases();
  for (const Chi2Case& c : cases) {
    if (c.warp.incidentDegrees > 80.f) continue;  // at 89° twice the roughness changes little that is seen
    BsdfWarp judge = c.warp;
    judge.bsdf.alpha *= 2.f;
    const Chi2Result r = chi2Test(bsdfChi2Domain(), bsdfSampleFunction(c.warp), bsdfPdfFunction(judge),
                                  bsdfChi2Options(int(cases.size())));
    EXPECT_FALSE(r.accepted) << c.name << " judged at twice its roughness";
  }
}

// GGX's visible-normal sampling judged by the density of sampling all normals (D cos θh): the pdfs
// differ by G1(wo) (wo·h) / ((n·h) cos θo), so the test rejects it away from normal incidence.
TEST(BsdfChi2, VisibleNormalsJudgedByAllNormalsAreRejected) {
  for (float theta : {40.f, 75.f}) {
    const BsdfWarp w{makeRoughConductor(MicrofacetDistribution::Ggx, 0.4f, Color3(1.f)), theta};
    const PdfFunction allNormals = [&](const Vec3& wi) {
      const Vec3 wo = w.wo();
      if (!(wi.z > 0.f)) return 0.0;
      const Vec3 h = glm::normalize(wo + wi);
      return double(microfacetD(MicrofacetDistribution::Ggx, h, 0.4f) * h.z / (4.f * glm::dot(wi, h)));
    };
    const Chi2Result r = chi2Test(bsdfChi2Domain(), bsdfSampleFunction(w), allNormals, bsdfChi2Options(2));
    EXPECT_FALSE(r.accepted) << theta;
  }
}

// A pdf scaled above 1 is refused by the rejected draws' cell even where the shape is right (a sharp
// lobe at normal incidence, which reflects no draw below the surface).
TEST(BsdfChi2, APdfIntegratingToMoreThanOneIsRejected) {
  const BsdfWarp w{makeRoughConductor(MicrofacetDistribution::Beckmann, 0.05f, Color3(1.f)), 0.f};
  const Chi2Result r =
      chi2Test(bsdfChi2Domain(), bsdfSampleFunction(w), bsdfPdfFunction(w, 1.01), bsdfChi2Options(1));
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.message.find("more than 1"), std::string::npos) << r.message;
}

// ---- extremes -------------------------------------------------------------------------------------

TEST(Bsdf, NoNanInfOrNegativeValueAtTheExtremes) {
  std::vector<Bsdf> bsdfs;
  for (float alpha : {kMinAlpha, 1e-4f, 1.f, 10.f, kMaxAlpha}) {
    bsdfs.push_back(makeMicrofacet(Color3(0.f), alpha, 1.5046f, 1.000277f));
    bsdfs.push_back(makeMicrofacet(Color3(1.f), alpha, 1.5046f, 1.000277f));
    bsdfs.push_back(makeMicrofacet(Color3(0.5f), alpha, 1.f, 1.f));  // IOR 1: no specular reflection
    bsdfs.push_back(makeRoughConductor(MicrofacetDistribution::Beckmann, alpha, Color3(1.f)));
    bsdfs.push_back(makeRoughConductor(MicrofacetDistribution::Ggx, alpha, Color3(1.f)));
  }
  const std::vector<Vec3> dirs = {Vec3(0, 0, 1),
                                  Vec3(direction(89.9, 0)),
                                  Vec3(direction(89.999, 30)),
                                  Vec3(direction(45, 0)),
                                  Vec3(direction(45, 180)),
                                  Vec3(1, 0, 0),
                                  Vec3(0.f, 1e-7f, 1.f),
                                  glm::normalize(Vec3(1.f, 0.f, 1e-6f))};
  Rng rng(5, 9);
  for (const Bsdf& b : bsdfs)
    for (const Vec3& wo0 : dirs) {
      const Vec3 wo = glm::normalize(wo0);
      const Vec3 mirror(-wo.x, -wo.y, wo.z);
      for (const Vec3& wi : {mirror, wo, Vec3(0, 0, 1), Vec3(direction(89.9, 180))}) {
        const Color3 f = evalBsdf(b, wo, wi);
        const float pdf = pdfBsdf(b, wo, wi);
        ASSERT_TRUE(isValidRadiance(f)) << nameOf(b);
        ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0.f) << nameOf(b) << " pdf " << pdf;
      }
      for (int i = 0; i < 2000; ++i) {
        const BsdfSample s = sampleBsdf(b, wo, Vec2(rng.nextFloat(), rng.nextFloat()));
        ASSERT_TRUE(isValidRadiance(s.weight)) << nameOf(b);
        ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf >= 0.f) << nameOf(b);
        if (s.pdf > 0.f) {
          ASSERT_GT(s.wi.z, 0.f);
          // The sample's density is the density pdfBsdf gives its direction.
          ASSERT_NEAR(s.pdf, pdfBsdf(b, wo, s.wi), 1e-5f * s.pdf) << nameOf(b);
        }
      }
    }
}

TEST(Bsdf, IorOneHasNoSpecularReflection) {
  const Bsdf b = makeMicrofacet(Color3(0.2f), 0.1f, 1.f, 1.f);
  const Vec3 wo(direction(30, 0)), mirror(direction(30, 180));
  EXPECT_NEAR(evalBsdf(b, wo, mirror).x, 0.2f * kInvPi, 1e-7f);
}

}  // namespace
}  // namespace penumbra
