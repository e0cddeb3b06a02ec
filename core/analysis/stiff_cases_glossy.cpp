// The glossy stiff cases: each reflection model where naive microfacet code breaks (near-mirror and
// very rough surfaces, grazing and horizon directions, the exact mirror direction, kd at 0 and 1, equal
// indices of refraction). A BSDF at one viewing direction is checked by drawing from its sampler:
// every weight (f cos θ / pdf) and density finite and non-negative, every draw's density the one
// pdfBsdf gives its direction, and the mean weight equal to the directional albedo by quadrature
// (bsdf_albedo.h), which holds only when sampling and density agree.
#include <cmath>
#include <string>
#include <vector>

#include "core/analysis/stiff_case_kit.h"
#include "core/materials/bsdf.h"
#include "core/materials/bsdf_albedo.h"
#include "core/math/float_util.h"
#include "core/sampling/rng.h"

namespace penumbra::analysis::kit {

namespace {

Vec3 atAngle(double degrees) {
  const double t = degrees * kPiD / 180.0;
  return Vec3(float(std::sin(t)), 0.f, float(std::cos(t)));
}

std::string label(const Bsdf& b, double degrees) {
  std::string type = b.type == BsdfType::Microfacet                  ? "microfacet kd " + num(b.albedo.x)
                     : b.distribution == MicrofacetDistribution::Ggx ? std::string("ggx")
                                                                     : std::string("beckmann");
  return type + " a " + num(b.alpha) + " at " + num(degrees) + " deg";
}

// n draws of b's sampler from wo: the mean weight against the quadrature albedo.
CaseResult draws(const Bsdf& b, const Vec3& wo, int n, uint64_t seed) {
  Rng rng(mix64(seed), seed);
  double sum = 0, sum2 = 0;
  uint64_t bad = 0, mismatched = 0;
  for (int i = 0; i < n; ++i) {
    const float u1 = rng.nextFloat();
    const BsdfSample s = sampleBsdf(b, wo, Vec2(u1, rng.nextFloat()));
    const double w = s.weight.x;
    if (!isValidRadiance(s.weight) || !(std::isfinite(s.pdf) && s.pdf >= 0.f)) {
      ++bad;
      continue;
    }
    if (s.pdf > 0.f && !(std::fabs(pdfBsdf(b, wo, s.wi) - s.pdf) <= 1e-4f * s.pdf)) ++mismatched;
    sum += w;
    sum2 += w * w;
  }
  Estimate e;
  e.mean = sum / n;
  e.standardError = std::sqrt(std::max(0.0, sum2 / n - e.mean * e.mean) / n);
  e.bad = bad;
  CaseResult r = fromEstimate(e, directionalAlbedo(b, wo));
  r.relSlack = 2e-4;  // the quadrature's error
  if (mismatched)
    r.failures.push_back(std::to_string(mismatched) + " draws whose pdf differs from pdfBsdf's");
  return r;
}

CaseResult drawsOf(const CaseOptions& o, const std::vector<Bsdf>& bsdfs, const std::vector<double>& angles) {
  CaseResult acc;
  bool first = true;
  uint64_t seed = o.seed;
  for (const Bsdf& b : bsdfs)
    for (double a : angles) merge(acc, draws(b, atAngle(a), count(o, 40000), seed++), label(b, a), first);
  return acc;
}

std::vector<Bsdf> everyModelAt(float alpha) {
  return {makeMicrofacet(Color3(0.3f), alpha, 1.5046f, 1.000277f),
          makeRoughConductor(MicrofacetDistribution::Beckmann, alpha, Color3(1.f)),
          makeRoughConductor(MicrofacetDistribution::Ggx, alpha, Color3(1.f))};
}

// A deterministic value check: v finite and non-negative, else a failure naming what.
void requireValid(CaseResult& r, float v, const std::string& what) {
  if (!(std::isfinite(v) && v >= 0.f)) {
    ++r.bad;
    r.failures.push_back(what + " = " + num(v));
  }
}

}  // namespace

CaseResult glossyNearMirror(const CaseOptions& o) {
  return drawsOf(o, everyModelAt(1e-4f), {0.0, 45.0, 80.0});
}

CaseResult glossyRough(const CaseOptions& o) {
  std::vector<Bsdf> bsdfs = everyModelAt(1.f);
  for (const Bsdf& b : everyModelAt(10.f)) bsdfs.push_back(b);
  return drawsOf(o, bsdfs, {0.0, 60.0});
}

CaseResult glossyGrazing(const CaseOptions& o) {
  std::vector<Bsdf> bsdfs = everyModelAt(0.05f);
  for (const Bsdf& b : everyModelAt(0.5f)) bsdfs.push_back(b);
  return drawsOf(o, bsdfs, {89.9});
}

// f and pdf at the exact mirror direction of wo, at wo itself and at the normal: finite and
// non-negative, and the mirror direction has positive density (the lobe's peak is reachable).
CaseResult glossyMirrorDirection(const CaseOptions&) {
  CaseResult r = exact(0.0, 0.0);
  r.statistical = false;
  for (float alpha : {1e-6f, 1e-4f, 0.1f, 1.f})
    for (const Bsdf& b : everyModelAt(alpha))
      for (double a : {0.0, 30.0, 89.9}) {
        const Vec3 wo = atAngle(a), mirror(-wo.x, -wo.y, wo.z);
        const std::string at = label(b, a);
        for (const Vec3& wi : {mirror, wo, Vec3(0.f, 0.f, 1.f)}) {
          requireValid(r, evalBsdf(b, wo, wi).x, "f " + at);
          requireValid(r, pdfBsdf(b, wo, wi), "pdf " + at);
        }
        if (!(pdfBsdf(b, wo, mirror) > 0.f))
          r.failures.push_back("no density at the mirror direction, " + at);
      }
  r.note = "f and pdf at wo's mirror direction, at wo and at the normal, alpha 1e-6 to 1";
  return r;
}

CaseResult glossyKdZeroAndOne(const CaseOptions& o) {
  CaseResult acc = drawsOf(o,
                           {makeMicrofacet(Color3(0.f), 0.1f, 1.5046f, 1.000277f),
                            makeMicrofacet(Color3(1.f), 0.1f, 1.5046f, 1.000277f)},
                           {0.0, 70.0});
  // kd = 1 leaves ks = 0: exactly the diffuse BSDF 1/π.
  const Bsdf one = makeMicrofacet(Color3(1.f), 0.1f, 1.5046f, 1.000277f);
  const float f = evalBsdf(one, atAngle(30), atAngle(-30)).x;
  if (f != kInvPi) acc.failures.push_back("kd 1: f = " + num(f) + ", not 1/pi");
  return acc;
}

// Directions in the surface (z = 0) or below it reflect nothing and are never drawn.
CaseResult glossyHorizon(const CaseOptions& o) {
  CaseResult r = exact(0.0, 0.0);
  r.statistical = false;
  const Vec3 horizon(1.f, 0.f, 0.f), other(0.f, 1.f, 0.f), justAbove = glm::normalize(Vec3(1.f, 0.f, 1e-7f));
  Rng rng(mix64(o.seed), o.seed);
  for (float alpha : {1e-4f, 0.1f, 1.f})
    for (const Bsdf& b : everyModelAt(alpha)) {
      const std::string at = label(b, 90.0);
      if (evalBsdf(b, horizon, other) != Color3(0.f) || pdfBsdf(b, horizon, other) != 0.f)
        r.failures.push_back("both directions in the surface reflect, " + at);
      for (const Vec3& wo : {horizon, justAbove})
        for (int i = 0; i < 1000; ++i) {
          const BsdfSample s = sampleBsdf(b, wo, Vec2(rng.nextFloat(), rng.nextFloat()));
          requireValid(r, s.pdf, "pdf of a draw from the horizon, " + at);
          if (!isValidRadiance(s.weight)) ++r.bad;
          if (s.pdf > 0.f && !(s.wi.z > 0.f)) r.failures.push_back("a draw at or below the surface, " + at);
          if (wo == horizon && s.pdf > 0.f) r.failures.push_back("a draw from wo in the surface, " + at);
        }
      requireValid(r, evalBsdf(b, justAbove, justAbove).x, "f just above the horizon, " + at);
    }
  r.note = "wo and wi in the surface, and wo 1e-7 above it";
  return r;
}

// intIOR = extIOR: the Fresnel term is 0, so microfacet is its diffuse part alone.
CaseResult glossyIorOne(const CaseOptions& o) {
  const Bsdf b = makeMicrofacet(Color3(0.4f), 0.1f, 1.f, 1.f);
  CaseResult acc = drawsOf(o, {b}, {0.0, 60.0});
  for (double a : {0.0, 40.0, 80.0}) {
    const Vec3 wo = atAngle(a), mirror(-wo.x, -wo.y, wo.z);
    if (evalBsdf(b, wo, mirror).x != 0.4f * kInvPi)
      acc.failures.push_back("IOR 1 reflects specularly at " + num(a) + " deg");
  }
  return acc;
}

}  // namespace penumbra::analysis::kit
