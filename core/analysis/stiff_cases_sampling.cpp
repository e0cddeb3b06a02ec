// The stiff cases of warps, samplers, tiny and near lights (the catalogue: stiff_cases.cpp; explained in
// docs/stiff-cases.md).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>

#include "core/analysis/closed_forms.h"
#include "core/analysis/stiff_case_kit.h"
#include "core/math/error.h"
#include "core/math/float_util.h"
#include "core/render/engine.h"
#include "core/render/film.h"
#include "core/render/strategy_axes.h"
#include "core/sampling/sampler.h"
#include "core/sampling/sampler_table.h"
#include "core/sampling/warp.h"

namespace penumbra::analysis::kit {

// ---- 1, 2: warps and samplers ------------------------------------------------------------------------

CaseResult warpExtremes(const CaseOptions& o) {
  const float us[] = {0.f, 0.5f, 1.f - 0x1p-24f};
  uint64_t bad = 0;
  std::vector<std::string> failures;
  for (int t = 0; t < kWarpTypeCount; ++t) {
    WarpType type = WarpType(t);
    float param = type == WarpType::Beckmann ? 0.2f : type == WarpType::UniformCone ? 0.5f : 0.f;
    for (float a : us)
      for (float b : us) {
        Vec3 v = Warp::warp(type, Vec2(a, b), param);
        float pdf = Warp::pdf(type, v, param);
        bool ok = isFinite(v) && std::isfinite(pdf) && pdf > 0.f;
        if (warpIsSpherical(type)) ok = ok && std::fabs(glm::length(v) - 1.f) < 1e-5f;
        if (!ok) {
          ++bad;
          failures.push_back(std::string(warpTypeName(type)) + " at (" + num(a) + ", " + num(b) + ")");
        }
      }
  }
  // No sampler ever returns 1.0; the draws are uniform (mean 1/2).
  const int n = count(o, 400000);
  double sum = 0;
  uint64_t draws = 0;
  for (const SamplerRow& row : samplerTable()) {
    Sampler sampler(row.kind, 64, o.seed);
    for (int i = 0; i < n / 8; ++i) {
      sampler.startPixelSample(IVec2(i % 13, i / 13), uint32_t(i * 2654435761u));
      for (int k = 0; k < 4; ++k) {
        float u = sampler.next1D();
        Vec2 u2 = sampler.next2D();
        for (float v : {u, u2.x, u2.y}) {
          if (!(v >= 0.f && v < 1.f)) ++bad;
          sum += v;
          ++draws;
        }
      }
    }
  }
  CaseResult r;
  r.expected = 0.5;
  r.estimate = sum / double(draws);
  r.standardError = std::sqrt(1.0 / 12.0 / double(draws));
  r.bad = bad;
  r.failures = failures;
  r.note = std::to_string(kWarpTypeCount) + " warps x 9 extreme inputs finite with pdf > 0; " +
           std::to_string(draws) + " sampler draws in [0, 1)";
  return r;
}

CaseResult diskAndCosineRim(const CaseOptions& o) {
  CaseResult r;
  const float top = 1.f - 0x1p-24f;
  Vec2 centre = Warp::squareToConcentricDisk(Vec2(0.5f, 0.5f));
  if (!(glm::length(centre) < 1e-6f))
    r.failures.push_back("concentric disk centre maps to " + num(glm::length(centre)));
  for (Vec2 u : {Vec2(0.f, 0.f), Vec2(top, 0.f), Vec2(0.f, top), Vec2(top, top)}) {
    Vec2 p = Warp::squareToConcentricDisk(u);
    float len = glm::length(p);
    if (!(len <= 1.f && len > 1.f - 1e-6f) || !(Warp::squareToConcentricDiskPdf(p) > 0.f)) ++r.bad;
  }
  // Rim of the cosine hemisphere: inputs where 1 − x² − y² rounds below 0 in float.
  uint64_t roundedNegative = 0;
  float minNaive = 1.f;
  for (int i = 0; i < 65536; ++i)
    for (int edge = 0; edge < 4; ++edge) {
      float t = float(i) / 65536.f, e = edge & 1 ? top : 0.f;
      Vec2 u = edge < 2 ? Vec2(e, t) : Vec2(t, e);
      Vec3 v = Warp::squareToCosineHemisphere(u);
      float naive = 1.f - v.x * v.x - v.y * v.y;  // what z² = 1 − x² − y² would give
      if (naive < 0.f) ++roundedNegative;
      minNaive = std::min(minNaive, naive);
      if (!isFinite(v) || !(v.z >= 0.f) || !(Warp::squareToCosineHemispherePdf(v) > 0.f) ||
          std::fabs(glm::length(v) - 1.f) > 1e-5f)
        ++r.bad;
    }
  // E[cos θ] under cosine sampling = 2/3.
  const int n = count(o, 200000);
  Sampler sampler(SamplerKind::Independent, 1, o.seed);
  double sum = 0, sumSq = 0;
  for (int i = 0; i < n; ++i) {
    sampler.startPixelSample(IVec2(3, 5), uint32_t(i));
    float z = Warp::squareToCosineHemisphere(sampler.next2D()).z;
    if (!(z >= 0.f) || !std::isfinite(z)) ++r.bad;
    sum += z;
    sumSq += double(z) * z;
  }
  r.expected = 2.0 / 3.0;
  r.estimate = sum / n;
  r.standardError = std::sqrt(std::max(0.0, sumSq / n - r.estimate * r.estimate) / (n - 1.0));
  r.note = "centre + 4 corners in the disk; " + std::to_string(roundedNegative) +
           " of 262144 rim inputs with 1-x^2-y^2 < 0 in float (min " + num(minNaive) +
           "); z from (1-|r|)(1+|r|) is finite and >= 0 for all; E[cos] = 2/3";
  return r;
}

// ---- 3: cone sampling of tiny / distant lights --------------------------------------------------------

CaseResult coneCase(const CaseOptions& o, const std::string& tag) {
  LoadedScene s = load(o, "cone-sin2-" + tag + ".xml");
  const Scene& scene = *s.scene;
  const SphereLight& light = scene.sphereLights.at(0);
  const glm::dvec3 x(kReceiver), c(light.sphere.center);
  const double d = glm::length(c - x), r = light.sphere.radius;
  const double sin2 = (r / d) * (r / d), cosMax = std::sqrt((d - r) / d * ((d + r) / d));
  // MIS: the cosine technique reaches the cone with probability ~sin²θmax and carries a share of up to
  // ~sin²θmax of the estimate (balance). Where that share exceeds the 1e-5 slack, enough samples for
  // ~40 such hits, or the rare hits make the sample variance (and so the z-test) meaningless.
  const int misSamples = sin2 > 1e-5 ? int(std::min(1e6, 40.0 / sin2)) : 0;
  CaseResult acc =
      directCase(o, "cone-sin2-" + tag + ".xml", kSolid | kMis, 20000, kReceiver, 1e-4f, 4, misSamples);
  // The sampled pdf agrees with pdfSolidAngle(wi) and with the closed form 1 / (2π (1 − cos θmax)).
  const double pdfTruth = 1.0 / (2.0 * kPiD * (sin2 / (1.0 + cosMax)));
  Sampler sampler(SamplerKind::Independent, 1, o.seed + 7);
  uint64_t mismatched = 0;
  const int n = count(o, 20000);
  for (int i = 0; i < n; ++i) {
    sampler.startPixelSample(IVec2(1, 2), uint32_t(i));
    LightSample ls = light.sampleSolidAngle(kReceiver, sampler.next2D());
    if (!(ls.pdf > 0.f) || !std::isfinite(ls.pdf)) {
      ++acc.bad;
      continue;
    }
    float back = light.pdfSolidAngle(kReceiver, ls.wi);
    if (std::fabs(ls.pdf / pdfTruth - 1.0) > 1e-5 || !(std::fabs(back / ls.pdf - 1.f) < 1e-5f)) ++mismatched;
  }
  if (mismatched)
    acc.failures.push_back(std::to_string(mismatched) +
                           " samples whose pdf disagrees with the closed form or pdfSolidAngle");
  acc.note += "; pdf = 1/(2pi(1-cos)) = " + num(pdfTruth) + " for all samples";
  return acc;
}

// ---- 4: radius 0, underflowing sin² ---------------------------------------------------------------------

CaseResult radiusZero(const CaseOptions& o) {
  LoadedScene s = load(o, "light-radius-0.xml");
  CaseResult r = exactlyZeroCase(o, "light-radius-0.xml", 2000);
  const SphereLight& light = s.scene->sphereLights.at(0);
  for (Vec2 u : {Vec2(0.f), Vec2(0.5f), Vec2(1.f - 0x1p-24f)}) {
    LightSample a = light.sampleArea(kReceiver, u), b = light.sampleSolidAngle(kReceiver, u);
    if (a.pdf != 0.f || b.pdf != 0.f) r.failures.push_back("a radius-0 light returned a sample");
  }
  if (light.pdfArea() != 0.f || light.pdfSolidAngle(kReceiver, kUp) != 0.f)
    r.failures.push_back("non-zero pdf");
  // No geometry: a ray from the receiver straight through the light's centre hits nothing.
  Ray up;
  up.o = kReceiver + Vec3(0.f, 0.f, 1e-3f);
  up.d = kUp;
  up.tMax = 1e3f;
  SurfaceHit hit;
  if (s.scene->geometry.intersect(up, hit)) r.failures.push_back("a radius-0 light was added as geometry");
  r.note = "builder keeps the light (" + std::to_string(s.scene->sphereLights.size()) +
           "), no geometry; no samples; every strategy exactly 0";
  return r;
}

CaseResult sin2Underflow(const CaseOptions& o) {
  LoadedScene s = load(o, "light-sin2-underflow.xml");
  const SphereLight& light = s.scene->sphereLights.at(0);
  CaseResult acc = directCase(o, "light-sin2-underflow.xml", kAll, 2000, kReceiver, 1e-4f, 1);
  // The cone is below the float pdf range (1 − cos θmax < 2^-120): no sample, so the estimate is 0;
  // the energy this drops is at most Le · 2π·2^-120 / π.
  acc.absSlack = double(light.radiance.x) * 0x1p-119;
  for (Vec2 u : {Vec2(0.f), Vec2(0.5f), Vec2(1.f - 0x1p-24f)}) {
    LightSample b = light.sampleSolidAngle(kReceiver, u), a = light.sampleArea(kReceiver, u);
    if (!std::isfinite(b.pdf) || !std::isfinite(a.pdf)) acc.failures.push_back("infinite pdf");
  }
  acc.note += "; slack Le*2^-119 = " + num(acc.absSlack);
  return acc;
}

// ---- 5: on, next to and inside the light's surface ------------------------------------------------------

namespace {

// Unoccluded irradiance factor I at x (normal n) by solid-angle (and area) sampling of `light`.
Estimate irradianceByApi(const SphereLight& light, const Vec3& x, const Vec3& n, bool area, int count,
                         uint64_t seed) {
  Sampler sampler(SamplerKind::Independent, 1, seed);
  double sum = 0, sumSq = 0;
  Estimate e;
  for (int i = 0; i < count; ++i) {
    sampler.startPixelSample(IVec2(4, 4), uint32_t(i));
    Vec2 u = sampler.next2D();
    LightSample ls = area ? light.sampleArea(x, u) : light.sampleSolidAngle(x, u);
    double v = 0;
    if (ls.pdf > 0.f) v = double(ls.Le.x) * std::max(0.f, glm::dot(n, ls.wi)) / double(ls.pdf);
    if (!std::isfinite(ls.pdf) || !(v >= 0.0) || !std::isfinite(v)) {
      ++e.bad;
      continue;
    }
    sum += v;
    sumSq += v * v;
  }
  e.mean = sum / count;
  e.standardError = std::sqrt(std::max(0.0, sumSq / count - e.mean * e.mean) / (count - 1.0));
  return e;
}

}  // namespace

CaseResult onSurface(const CaseOptions& o) {
  // x on the plane z = 0; centre (3, 0, -4) away, r = 5: |c − x| = r exactly, θ ≈ 143°.
  SphereLight light;
  light.sphere.center = Vec3(3.25f, 0.5f, -4.f);
  light.sphere.radius = 5.f;
  light.radiance = Color3(1.f);
  const Vec3 x(0.25f, 0.5f, 0.f);
  double truth =
      sphereLightIrradianceFactor(glm::dvec3(x), glm::dvec3(kUp), glm::dvec3(light.sphere.center), 5.0);
  CaseResult r = fromEstimate(irradianceByApi(light, x, kUp, false, count(o, 20000), o.seed), truth);
  // Area sampling sees only the back of every point (a one-sided emitter from its own surface): 0.
  Estimate area = irradianceByApi(light, x, kUp, true, count(o, 2000), o.seed + 1);
  r.bad += area.bad;
  if (area.mean != 0.0)
    r.failures.push_back("area sampling from the surface gave " + num(area.mean) + ", expected 0");
  r.note = "I = (pi/2)(1+cos theta) by solid angle; area: exactly 0 (every point faces away)";
  return r;
}

CaseResult outside1e8(const CaseOptions& o) {
  // Float centre whose distance (in double) from x is r (1 + 1e-8): searched over a few ulps.
  const Vec3 x(0.25f, 0.5f, 0.f);
  const double target = 1.0 + 1e-8;
  Vec3 best(0.f);
  double bestErr = 1e30;
  auto ulpsBelow = [](float v, int k) {
    for (int i = 0; i < k; ++i) v = std::nextafter(v, -1.f);
    return v;
  };
  float cx = ulpsBelow(0.25f + 0.6f * float(target), 24);
  for (int i = 0; i < 48; ++i, cx = std::nextafter(cx, 2.f)) {
    float cz = ulpsBelow(0.8f * float(target), 24);
    for (int j = 0; j < 48; ++j, cz = std::nextafter(cz, 2.f)) {
      double d = glm::length(glm::dvec3(cx, 0.5, cz) - glm::dvec3(x));
      if (std::fabs(d - target) < bestErr) {
        bestErr = std::fabs(d - target);
        best = Vec3(cx, 0.5f, cz);
      }
    }
  }
  SphereLight light;
  light.sphere.center = best;
  light.sphere.radius = 1.f;
  light.radiance = Color3(1.f);
  const double gap = glm::length(glm::dvec3(best) - glm::dvec3(x)) - 1.0;
  double truth = sphereLightIrradianceFactor(glm::dvec3(x), glm::dvec3(kUp), glm::dvec3(best), 1.0);
  CaseResult r = fromEstimate(irradianceByApi(light, x, kUp, false, count(o, 20000), o.seed), truth);
  if (!(gap > 0.5e-8 && gap < 2e-8))
    r.failures.push_back("could not place the light 1e-8 r away (gap " + num(gap) + ")");
  r.note = "gap (d-r)/r = " + num(gap) + " (double from float positions), solid angle";
  return r;
}

CaseResult inside(const CaseOptions& o) {
  LoadedScene s = load(o, "light-inside.xml");
  const SphereLight& light = s.scene->sphereLights.at(0);
  // The camera ray starts inside the light, over the receiver.
  Ray ray = rayOnto(kReceiver, kUp, 0.05f);
  CaseResult acc;
  bool first = true;
  int n = count(o, 4000);
  merge(acc, fromEstimate(estimate(directByLight(LightMeasure::SolidAngle), *s.scene, ray, n, o.seed), 0.0),
        nameOf(directByLight(LightMeasure::SolidAngle)), first);
  merge(acc, fromEstimate(estimate(directByLight(LightMeasure::Area), *s.scene, ray, n, o.seed), 0.0),
        nameOf(directByLight(LightMeasure::Area)), first);
  merge(acc,
        fromEstimate(estimate(directByHemisphere(HemisphereWarp::Cosine), *s.scene, ray, n, o.seed), 0.0),
        nameOf(directByHemisphere(HemisphereWarp::Cosine)), first);
  acc.relSlack = 0;
  double truth = sphereLightIrradianceFactor(glm::dvec3(kReceiver), glm::dvec3(kUp),
                                             glm::dvec3(light.sphere.center), light.sphere.radius);
  if (truth != 0.0) acc.failures.push_back("closed form inside a one-sided light is " + num(truth));
  return acc;
}

}  // namespace penumbra::analysis::kit
