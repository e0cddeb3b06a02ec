// The stiff-case catalogue; see stiff_cases.h and docs/stiff-cases.md (one section per case).
#include "core/analysis/stiff_cases.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>

#include "core/analysis/closed_forms.h"
#include "core/analysis/ray_estimate.h"
#include "core/math/error.h"
#include "core/math/float_util.h"
#include "core/render/engine.h"
#include "core/render/film.h"
#include "core/render/strategy_table.h"
#include "core/sampling/sampler.h"
#include "core/sampling/sampler_table.h"
#include "core/sampling/warp.h"
#include "core/scene/scene_builder.h"

#ifndef PENUMBRA_STIFF_SCENE_DIR
#define PENUMBRA_STIFF_SCENE_DIR "scenes/stiff"
#endif

namespace penumbra::analysis {

// ---- verdicts -------------------------------------------------------------------------------------

double CaseResult::tolerance() const {
  return 4.0 * standardError + absSlack + relSlack * std::fabs(expected);
}

double CaseResult::zScore() const {
  if (!statistical) return 0.0;
  // Distance beyond the rounding slack, in standard errors.
  double beyond = std::fabs(estimate - expected) - absSlack - relSlack * std::fabs(expected);
  if (!(beyond > 0.0)) return std::isnan(beyond) ? std::numeric_limits<double>::infinity() : 0.0;
  return standardError > 0.0 ? beyond / standardError : std::numeric_limits<double>::infinity();
}

bool CaseResult::passed() const {
  if (bad != 0 || !failures.empty()) return false;
  if (!statistical) return true;
  if (!std::isfinite(estimate) || !std::isfinite(expected)) return false;
  return zScore() <= 4.0;
}

std::string defaultStiffSceneDir() {
  if (const char* env = std::getenv("PENUMBRA_STIFF_SCENES"); env && *env) return env;
  if (std::filesystem::is_directory("scenes/stiff")) return "scenes/stiff";
  return PENUMBRA_STIFF_SCENE_DIR;
}

namespace {

const Vec3 kUp(0.f, 0.f, 1.f);
const Vec3 kReceiver(0.31f, 0.17f, 0.f);  // the receiver point of the plane scenes (generate.py: X)

std::string sceneDir(const CaseOptions& o) {
  return o.sceneDir.empty() ? defaultStiffSceneDir() : o.sceneDir;
}
LoadedScene load(const CaseOptions& o, const std::string& file) {
  return loadScene(sceneDir(o) + "/" + file);
}
int count(const CaseOptions& o, int n) {
  return o.quick ? std::max(1000, n / 8) : n;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Folds a sub-check into a case: the row shows the sub-check with the largest z-score (a failing one
// first); bad counts and failures accumulate; the note lists every sub-check.
void merge(CaseResult& acc, const CaseResult& sub, const std::string& label, bool& first) {
  acc.bad += sub.bad;
  for (const std::string& f : sub.failures) acc.failures.push_back(label + ": " + f);
  if (!acc.note.empty()) acc.note += "; ";
  acc.note += label + " " +
              (sub.statistical ? num(sub.estimate) + "±" + num(sub.standardError) : "finite-only") +
              (sub.bad ? " (" + std::to_string(sub.bad) + " bad)" : "");
  if (!sub.statistical) return;
  bool worse = first || (!sub.passed() && acc.passed()) ||
               (sub.passed() == acc.passed() && sub.zScore() > acc.zScore());
  if (worse) {
    std::vector<std::string> keepFailures = std::move(acc.failures);
    uint64_t keepBad = acc.bad;
    std::string keepNote = std::move(acc.note);
    acc = sub;
    acc.failures = std::move(keepFailures);
    acc.bad = keepBad;
    acc.note = std::move(keepNote);
    first = false;
  }
}

CaseResult fromEstimate(const Estimate& e, double expected) {
  CaseResult r;
  r.expected = expected;
  r.estimate = e.mean;
  r.standardError = e.standardError;
  r.bad = e.bad;
  return r;
}

CaseResult exact(double expected, double estimate, uint64_t bad = 0, double absSlack = 0.0) {
  CaseResult r;
  r.expected = expected;
  r.estimate = estimate;
  r.bad = bad;
  r.absSlack = absSlack;
  r.relSlack = 0.0;
  return r;
}

CaseResult finiteOnly(const Estimate& e) {
  CaseResult r = fromEstimate(e, 0.0);
  r.statistical = false;
  return r;
}

// Reflected radiance Lr of the albedo-1 receiver at x (normal n) lit by every sphere light.
double directTruth(const Scene& scene, const Vec3& x, const Vec3& n = kUp) {
  double sum = 0;
  for (const SphereLight& l : scene.sphereLights)
    sum += double(l.radiance.x) / kPiD *
           sphereLightIrradianceFactor(glm::dvec3(x), glm::dvec3(n), glm::dvec3(l.sphere.center),
                                       double(l.sphere.radius));
  return sum;
}

// One strategy's estimate along `ray`, one shading sample per camera sample (the strategy table's
// instance of its integrator).
Estimate estimate(Strategy s, const Scene& scene, const Ray& ray, int n, uint64_t seed) {
  return strategyRow(s).estimateRay(scene, ray, 1, n, seed, SamplerKind::Independent);
}

std::string nameOf(Strategy s) {
  return std::string(strategyRow(s).shortName);
}

// The strategies a case runs, as bits of Strategy.
constexpr unsigned bit(Strategy s) {
  return 1u << unsigned(s);
}
// The mis rows: every light measure with both heuristics (one light and one cosine sample each).
constexpr Strategy kMisRows[] = {Strategy::DirectMisSolidAnglePower, Strategy::DirectMisSolidAngleBalance,
                                 Strategy::DirectMisAreaPower,       Strategy::DirectMisAreaBalance,
                                 Strategy::DirectMisProjectedPower,  Strategy::DirectMisProjectedBalance};
constexpr unsigned kSolid = bit(Strategy::DirectSolidAngle), kArea = bit(Strategy::DirectArea),
                   kProjected = bit(Strategy::DirectProjectedSolidAngle),
                   kCosine = bit(Strategy::DirectCosineHemisphere),
                   kUniform = bit(Strategy::DirectUniformHemisphere),
                   kMis = bit(kMisRows[0]) | bit(kMisRows[1]) | bit(kMisRows[2]) | bit(kMisRows[3]) |
                          bit(kMisRows[4]) | bit(kMisRows[5]),
                   kAll = kSolid | kArea | kProjected | kCosine | kUniform | kMis;

// Direct lighting of the receiver point by each strategy in `strategies`: light sampling first, then
// hemisphere sampling (which needs no area light) with hemisphereFactor times the samples, then the
// mis rows with misSamples (0: n); the i-th strategy of that order uses seed + i.
CaseResult directCase(const CaseOptions& o, const std::string& file, unsigned strategies, int n,
                      const Vec3& x = kReceiver, float slope = 1e-4f, int hemisphereFactor = 4,
                      int misSamples = 0) {
  LoadedScene s = load(o, file);
  const Scene& scene = *s.scene;
  Ray ray = shallowRayOnto(x, slope);
  CaseResult acc;
  SurfaceHit hit;
  if (!scene.geometry.intersect(ray, hit) || scene.materials[hit.objectId].sphereLight >= 0) {
    acc.failures.push_back("the camera ray does not reach the receiver");
    return acc;
  }
  // The truth at the point the integrator actually shades (float rounding of the hit point matters
  // for receivers 1e-6 r from a light).
  double truth = directTruth(scene, hit.p);
  bool first = true;
  n = count(o, n);
  const Strategy order[] = {Strategy::DirectSolidAngle,
                            Strategy::DirectArea,
                            Strategy::DirectProjectedSolidAngle,
                            Strategy::DirectCosineHemisphere,
                            Strategy::DirectUniformHemisphere,
                            kMisRows[0],
                            kMisRows[1],
                            kMisRows[2],
                            kMisRows[3],
                            kMisRows[4],
                            kMisRows[5]};
  for (unsigned i = 0; i < std::size(order); ++i) {
    if (!(strategies & bit(order[i]))) continue;
    const bool mis = kMis & bit(order[i]);
    int samples = mis && misSamples > 0                                  ? misSamples
                  : strategyRow(order[i]).needs == SceneNeed::AreaLights ? n
                                                                         : hemisphereFactor * n;
    merge(acc, fromEstimate(estimate(order[i], scene, ray, samples, o.seed + i), truth), nameOf(order[i]),
          first);
  }
  return acc;
}

// A case whose answer is exactly 0 for every strategy (no slack: 0 must come out as 0).
CaseResult exactlyZeroCase(const CaseOptions& o, const std::string& file, int n) {
  CaseResult acc = directCase(o, file, kAll, n, kReceiver, 1e-4f, 1);
  acc.absSlack = 0;
  acc.relSlack = 0;
  if (acc.failures.empty() && !(acc.expected == 0.0 && acc.estimate == 0.0 && acc.standardError == 0.0))
    acc.failures.push_back("expected exactly 0, got " + num(acc.estimate) + " (truth " + num(acc.expected) +
                           ")");
  return acc;
}

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
  merge(acc, fromEstimate(estimate(Strategy::DirectSolidAngle, *s.scene, ray, n, o.seed), 0.0),
        nameOf(Strategy::DirectSolidAngle), first);
  merge(acc, fromEstimate(estimate(Strategy::DirectArea, *s.scene, ray, n, o.seed), 0.0),
        nameOf(Strategy::DirectArea), first);
  merge(acc, fromEstimate(estimate(Strategy::DirectCosineHemisphere, *s.scene, ray, n, o.seed), 0.0),
        nameOf(Strategy::DirectCosineHemisphere), first);
  acc.relSlack = 0;
  double truth = sphereLightIrradianceFactor(glm::dvec3(kReceiver), glm::dvec3(kUp),
                                             glm::dvec3(light.sphere.center), light.sphere.radius);
  if (truth != 0.0) acc.failures.push_back("closed form inside a one-sided light is " + num(truth));
  return acc;
}

// ---- 9: scale invariance ------------------------------------------------------------------------------

struct Render {
  Image mean, se;
  uint64_t bad = 0;
};

// The scene's own integrator, or `strategy` when given.
Render render(const LoadedScene& s, uint32_t spp, uint64_t seed, std::optional<Strategy> strategy = {}) {
  auto job = std::make_shared<RenderJob>();
  job->scene = s.scene;
  job->settings = s.settings;
  job->settings.seed = seed;
  if (strategy) job->settings.integrator.strategy = *strategy;
  Engine engine;
  RenderLimits limits;
  limits.targetSpp = spp;
  engine.start(job, limits, 2);
  engine.wait();
  RenderProgress p = engine.progress();
  return Render{engine.film().mean(p.spp), engine.film().standardError(p.spp), p.badSamples};
}

void imageMean(const Render& r, double& mean, double& se) {
  double sum = 0, var = 0;
  size_t n = r.mean.pixelCount();
  for (size_t i = 0; i < n; ++i) {
    sum += r.mean.rgb[3 * i];
    var += double(r.se.rgb[3 * i]) * r.se.rgb[3 * i];
  }
  mean = sum / double(n);
  se = std::sqrt(var) / double(n);
}

CaseResult scaleCase(const CaseOptions& o, const std::string& kind, std::optional<Strategy> strategy = {}) {
  const uint32_t spp = o.quick ? 16 : 64;
  Render ref = render(load(o, "scale-" + kind + "-1.xml"), spp, o.seed, strategy);
  double m1, se1;
  imageMean(ref, m1, se1);
  CaseResult acc;
  bool first = true;
  acc.bad = ref.bad;
  for (const char* tag : {"1e-4", "1e4"}) {
    Render img = render(load(o, "scale-" + kind + "-" + tag + ".xml"), spp, o.seed, strategy);
    double m, se;
    imageMean(img, m, se);
    CaseResult sub;
    sub.expected = m1;
    sub.estimate = m;
    sub.standardError = std::sqrt(se * se + se1 * se1);
    sub.bad = img.bad;
    // Per pixel: the same sample streams at every scale, so pixels agree far within noise; count
    // the ones that differ by more than 4 combined standard errors (acne, lost contact shadows).
    size_t outliers = 0, n = img.mean.pixelCount();
    for (size_t i = 0; i < n; ++i) {
      double a = img.mean.rgb[3 * i], b = ref.mean.rgb[3 * i];
      double s = std::hypot(double(img.se.rgb[3 * i]), double(ref.se.rgb[3 * i]));
      if (std::fabs(a - b) > 4.0 * s + 1e-3 * std::max(1.0, std::fabs(b))) ++outliers;
    }
    if (outliers > n / 100)
      sub.failures.push_back(std::to_string(outliers) + " of " + std::to_string(n) +
                             " pixels differ from scale 1");
    merge(acc, sub, std::string("scale ") + tag + " (" + std::to_string(outliers) + " px off)", first);
  }
  return acc;
}

// ---- 10: AO near the contact point of a resting sphere ------------------------------------------------

CaseResult aoOnSphereNearContact(const CaseOptions& o) {
  LoadedScene s = load(o, "resting-sphere.xml");
  CaseResult acc;
  bool first = true;
  for (double psiDeg : {170.0, 175.0}) {
    double psi = psiDeg * kPiD / 180.0;
    Vec3 n(float(std::sin(psi)), 0.f, float(std::cos(psi)));
    Vec3 p = Vec3(0, 0, 1) + n;
    Ray ray = rayOnto(p, n, 1e-3f);
    CaseResult sub = fromEstimate(estimate(Strategy::AoCosine, *s.scene, ray, count(o, 60000), o.seed),
                                  aoOnRestingConvexBody(psi));
    merge(acc, sub, "psi " + num(psiDeg), first);
  }
  acc.note += " (-> (pi-psi)^2/4)";
  return acc;
}

CaseResult aoOnPlaneNearContact(const CaseOptions& o) {
  LoadedScene s = load(o, "resting-sphere.xml");
  CaseResult acc;
  bool first = true;
  for (float rho : {0.05f, 0.1f}) {
    Ray ray = rayOnto(Vec3(rho, 0, 0), kUp, 5e-4f);
    CaseResult sub = fromEstimate(estimate(Strategy::AoCosine, *s.scene, ray, count(o, 60000), o.seed),
                                  aoPlaneNearRestingSphere(rho, 1.0));
    merge(acc, sub, "rho " + num(rho), first);
  }
  acc.note += " (~ 1.5 rho^2/R^2)";
  return acc;
}

// ---- 11: area sampling's far side ---------------------------------------------------------------------

CaseResult areaFarSide(const CaseOptions& o) {
  LoadedScene s = load(o, "light-straddling.xml");
  const SphereLight& light = s.scene->sphereLights.at(0);
  const int n = count(o, 40000);
  Sampler sampler(SamplerKind::Independent, 1, o.seed);
  uint64_t far = 0, bad = 0, leaking = 0;
  for (int i = 0; i < n; ++i) {
    sampler.startPixelSample(IVec2(9, 9), uint32_t(i));
    LightSample ls = light.sampleArea(kReceiver, sampler.next2D());
    if (!std::isfinite(ls.pdf) || !(ls.pdf >= 0.f)) ++bad;
    if (glm::dot(glm::dvec3(ls.n), glm::dvec3(kReceiver) - glm::dvec3(ls.p)) <= 0.0) {
      ++far;
      if (!isBlack(ls.Le)) ++leaking;
    }
  }
  // Fraction of the sphere's area hidden behind its own horizon: (1 + r/d) / 2.
  double d = glm::length(glm::dvec3(light.sphere.center) - glm::dvec3(kReceiver));
  double pFar = 0.5 * (1.0 + light.sphere.radius / d);
  CaseResult acc;
  bool first = true;
  CaseResult frac;
  frac.expected = pFar;
  frac.estimate = double(far) / n;
  frac.standardError = std::sqrt(pFar * (1 - pFar) / n);
  frac.bad = bad;
  if (leaking) frac.failures.push_back(std::to_string(leaking) + " far-side samples carry radiance");
  merge(acc, frac, "far-side fraction", first);
  CaseResult est = directCase(o, "light-straddling.xml", kArea, 40000);
  merge(acc, est, "area estimate", first);
  return acc;
}

// ---- 12: bright and occluded; radiance 0 -----------------------------------------------------------------

CaseResult brightOccluded(const CaseOptions& o) {
  LoadedScene s = load(o, "bright-occluded.xml");
  const Scene& scene = *s.scene;
  const SphereLight& light = scene.sphereLights.at(0);
  // Coaxial cones around the normal: Lr = Le (sin²αL − sin²αO) (albedo 1). The occluder is the
  // other sphere of the file; its values come from the description.
  double rO = 0, dO = 0;
  for (const SceneNode& node : s.desc.children)
    if (node.tag == "shape" && node.type == "sphere" && !node.child("emitter")) {
      Vec3 c = node.props.getPoint({"center"}, Vec3(0));
      rO = node.props.getFloat({"radius"}, 1.f);
      dO = glm::length(glm::dvec3(c) - glm::dvec3(kReceiver));
    }
  double dL = glm::length(glm::dvec3(light.sphere.center) - glm::dvec3(kReceiver)), rL = light.sphere.radius;
  double truth = double(light.radiance.x) * ((rL / dL) * (rL / dL) - (rO / dO) * (rO / dO));
  Ray ray = shallowRayOnto(kReceiver);
  CaseResult acc;
  bool first = true;
  int n = count(o, 40000);
  merge(acc, fromEstimate(estimate(Strategy::DirectSolidAngle, scene, ray, n, o.seed), truth),
        nameOf(Strategy::DirectSolidAngle), first);
  merge(acc, fromEstimate(estimate(Strategy::DirectArea, scene, ray, n, o.seed + 1), truth),
        nameOf(Strategy::DirectArea), first);
  // Hemisphere sampling finds the visible ring with probability ~2e-4: 400k samples (~80 hits) even
  // in --quick, so the standard error is itself estimated well enough for a z-test.
  merge(acc, fromEstimate(estimate(Strategy::DirectCosineHemisphere, scene, ray, 400000, o.seed + 2), truth),
        nameOf(Strategy::DirectCosineHemisphere), first);
  // MIS: the light samples carry the estimate; a cosine direction that finds the visible ring weighs
  // 1e6 by a weight near 0.
  for (unsigned i = 0; i < std::size(kMisRows); ++i)
    merge(acc, fromEstimate(estimate(kMisRows[i], scene, ray, n, o.seed + 3 + i), truth), nameOf(kMisRows[i]),
          first);
  return acc;
}

// ---- 13, 14: values the builder must reject -------------------------------------------------------------

struct Rejection {
  const char* file;
  const char* message;
};

CaseResult rejectAll(const CaseOptions& o, std::initializer_list<Rejection> list) {
  CaseResult acc = exact(double(list.size()), 0.0);
  for (const Rejection& rj : list) {
    CaseResult r = checkRejected(o, rj.file, rj.message);
    if (r.passed()) acc.estimate += 1;
    for (const std::string& f : r.failures) acc.failures.push_back(f);
  }
  acc.note = "files rejected with file:line and the expected message";
  return acc;
}

CaseResult badValues(const CaseOptions& o) {
  CaseResult acc = rejectAll(
      o,
      {{"bad-nan.xml", "expected a finite number, got \"nan\""},
       {"bad-inf.xml", "expected a finite number, got \"inf\""},
       {"bad-1e999.xml", "expected a finite number, got \"1e999\""},
       {"bad-sampleCount-0.xml", "sampleCount must be an integer in [1, 16777216], got 0"},
       {"bad-sampleCount--4.xml", "sampleCount must be an integer in [1, 16777216], got -4"},
       {"bad-sampleCount-4294967296.xml", "sampleCount must be an integer in [1, 16777216], got 4294967296"},
       {"bad-sampleCount-3.5.xml", "expected an integer"}});
  // -0 is accepted and read as +0: a radius-0 light (kept, no geometry).
  acc.expected += 1;
  try {
    LoadedScene s = load(o, "minus-zero.xml");
    float r = s.scene->sphereLights.at(0).sphere.radius;
    if (r == 0.f && !std::signbit(r))
      acc.estimate += 1;
    else
      acc.failures.push_back("-0 radius read as " + num(r));
  } catch (const std::exception& e) {
    acc.failures.push_back(std::string("-0 rejected: ") + e.what());
  }
  acc.note += "; -0 accepted as +0";
  return acc;
}

CaseResult degenerateMesh(const CaseOptions& o) {
  LoadedScene s = load(o, "degenerate-mesh.xml");
  bool warned = false;
  for (const std::string& w : s.warnings)
    warned = warned || w.find("dropped 3 degenerate") != std::string::npos;
  Render img = render(s, o.quick ? 4 : 16, o.seed);
  double m, se;
  imageMean(img, m, se);
  // An unoccluded plane has AO exactly 1 in every pixel.
  CaseResult r = exact(1.0, m, img.bad, 1e-6);
  if (!warned) r.failures.push_back("no warning about the 3 degenerate triangles");
  r.note = "3 degenerate triangles (collinear, repeated vertices) dropped with a warning; no normals; AO = 1";
  return r;
}

CaseResult cameraFov(const CaseOptions& o) {
  return rejectAll(o, {{"bad-fov-0.xml", "fov must be in (0, 180) degrees, got 0"},
                       {"bad-fov-180.xml", "fov must be in (0, 180) degrees, got 180"}});
}

// ---- 15: accumulation ----------------------------------------------------------------------------------

CaseResult accumulation(const CaseOptions& o) {
  (void)o;
  const int n = 1000000;
  Film film(2, 1);
  float naive0 = 0.f;
  const float a = 0.1f, big = 1e4f, small = 1e-3f;
  for (int i = 0; i < n; ++i) {
    film.add(0, 0, Color3(a));
    film.add(1, 0, Color3(i % 2 ? big : small));
    naive0 += a;
  }
  Image mean = film.mean(n), se = film.standardError(n);
  double expected0 = double(a), expected1 = 0.5 * (double(big) + double(small));
  CaseResult r = exact(expected1, mean.rgb[3], 0, 0x1p-23 * expected1);
  CaseResult r0 = exact(expected0, mean.rgb[0], 0, 0x1p-23 * expected0);
  if (!r0.passed()) r.failures.push_back("constant 0.1 drifted to " + num(mean.rgb[0]));
  if (!std::isfinite(se.rgb[0]) || !(se.rgb[0] >= 0.f) || se.rgb[0] > 1e-6f * a)
    r.failures.push_back("standard error of a constant pixel is " + num(se.rgb[0]));
  double seBig = 0.5 * (double(big) - double(small)) / std::sqrt(double(n - 1));
  if (!(std::fabs(se.rgb[3] / seBig - 1.0) < 1e-4))
    r.failures.push_back("standard error " + num(se.rgb[3]) + " vs " + num(seBig));
  r.note = "10^6 samples: 0.1 -> " + num(mean.rgb[0]) + " (a float sum gives " + num(naive0 / n) +
           "); alternating 1e4/1e-3";
  return r;
}

// Equal power: the closed form at the receiver must not depend on r (Le r² fixed, fully above).
void equalPowerTruths(const CaseOptions& o, const std::string& file, CaseResult& r) {
  double t1 = directTruth(*load(o, "equal-power-r1.xml").scene, kReceiver);
  double t = directTruth(*load(o, file).scene, kReceiver);
  if (std::fabs(t / t1 - 1.0) > 1e-6)
    r.failures.push_back("closed form " + num(t) + " differs from r = 1: " + num(t1));
}

std::vector<StiffCase> makeCases() {
  std::vector<StiffCase> v;
  auto add = [&](std::string name, std::string category, std::string description,
                 std::function<CaseResult(const CaseOptions&)> f) {
    v.push_back(StiffCase{std::move(name), std::move(category), std::move(description), std::move(f)});
  };
  add("warp-extremes", "warp-extremes", "every warp at u in {0, 0.5, 1-2^-24}^2; samplers never return 1.0",
      warpExtremes);
  add("disk-corners-cosine-rim", "warp-extremes",
      "concentric disk centre and corners; cosine hemisphere at the rim", diskAndCosineRim);
  for (const char* tag : {"1e-4", "1e-6", "1e-8", "1e-12"})
    add(std::string("cone-sin2-") + tag, "narrow-cone",
        std::string("solid-angle sampling, sin^2 theta_max = ") + tag,
        [tag](const CaseOptions& o) { return coneCase(o, tag); });
  add("light-radius-0", "tiny-light", "radius-0 light: kept, no geometry, no sample, exactly 0", radiusZero);
  add("light-sin2-underflow", "tiny-light", "r = 1e-25 at distance 1: finite, no infinite pdf",
      sin2Underflow);
  add("light-on-surface", "near-light", "shading point exactly on the light's surface", onSurface);
  add("light-outside-1e-6r", "near-light", "receiver 1e-6 r outside an overhead light (integrator)",
      [](const CaseOptions& o) {
        return directCase(o, "light-touching.xml", kSolid | kProjected | kCosine | kMis, 20000, kReceiver,
                          1e-5f, 1);
      });
  add("light-outside-1e-8r", "near-light", "shading point 1e-8 r outside the light", outside1e8);
  add("light-inside", "near-light", "receiver inside a one-sided light: exactly 0", inside);
  add("light-below-horizon", "horizon", "light entirely below the horizon: exactly 0",
      [](const CaseOptions& o) { return exactlyZeroCase(o, "light-below-horizon.xml", 4000); });
  add("light-straddling", "horizon", "light straddling the horizon", [](const CaseOptions& o) {
    return directCase(o, "light-straddling.xml", kSolid | kProjected | kArea | kCosine | kMis, 20000);
  });
  add("light-centre-on-horizon", "horizon", "light centre exactly on the horizon", [](const CaseOptions& o) {
    return directCase(o, "light-centre-on-horizon.xml", kSolid | kProjected | kArea | kCosine | kMis, 20000);
  });
  add("light-grazing-89.9", "horizon", "light centre 89.9 degrees from the normal", [](const CaseOptions& o) {
    return directCase(o, "light-grazing.xml", kSolid | kProjected | kArea | kCosine | kMis, 20000);
  });
  add("equal-power-r1", "equal-power", "equal power, r = 1 (all strategies)",
      [](const CaseOptions& o) { return directCase(o, "equal-power-r1.xml", kAll, 20000); });
  add("equal-power-r1e-3", "equal-power", "equal power, r = 1e-3 (light sampling, mis; hemisphere finite)",
      [](const CaseOptions& o) {
        CaseResult r = directCase(o, "equal-power-r1e-3.xml", kSolid | kProjected | kArea | kMis, 20000);
        equalPowerTruths(o, "equal-power-r1e-3.xml", r);
        return r;
      });
  add("equal-power-r1e-6", "equal-power", "equal power, r = 1e-6 (light sampling, mis; hemisphere finite)",
      [](const CaseOptions& o) {
        CaseResult r = directCase(o, "equal-power-r1e-6.xml", kSolid | kProjected | kArea | kMis, 20000);
        LoadedScene s = load(o, "equal-power-r1e-6.xml");
        bool first = false;
        Ray ray = shallowRayOnto(kReceiver);
        merge(r,
              finiteOnly(estimate(Strategy::DirectCosineHemisphere, *s.scene, ray, count(o, 20000), o.seed)),
              nameOf(Strategy::DirectCosineHemisphere), first);
        merge(r,
              finiteOnly(estimate(Strategy::DirectUniformHemisphere, *s.scene, ray, count(o, 20000), o.seed)),
              nameOf(Strategy::DirectUniformHemisphere), first);
        equalPowerTruths(o, "equal-power-r1e-3.xml", r);
        return r;
      });
  add("scale-ao", "scale", "AO image at scales 1e-4 and 1e4 vs 1",
      [](const CaseOptions& o) { return scaleCase(o, "ao"); });
  add("scale-direct", "scale", "direct image at scales 1e-4 and 1e4 vs 1",
      [](const CaseOptions& o) { return scaleCase(o, "direct"); });
  const std::pair<Strategy, const char*> misScales[] = {{kMisRows[0], "scale-mis-solid-angle"},
                                                        {kMisRows[3], "scale-mis-area"},
                                                        {kMisRows[4], "scale-mis-projected"}};
  for (const auto& [row, name] : misScales) {
    const Strategy mis = row;  // a plain copy: clang before 16 cannot capture a structured binding
    add(name, "scale", "direct image at scales 1e-4 and 1e4 vs 1, " + std::string(strategyRow(mis).label),
        [mis](const CaseOptions& o) { return scaleCase(o, "direct", mis); });
  }
  add("ao-sphere-near-contact", "contact", "AO on a resting sphere near its contact point",
      aoOnSphereNearContact);
  add("ao-plane-near-contact", "contact", "AO on the plane next to the contact point", aoOnPlaneNearContact);
  add("area-far-side", "far-side", "area sampling: far-side samples add exactly 0, unbiased", areaFarSide);
  add("radiance-1e6-occluded", "radiance-extremes", "radiance 1e6 with 98% of the light occluded",
      brightOccluded);
  add("radiance-0", "radiance-extremes", "radiance 0: exactly 0",
      [](const CaseOptions& o) { return exactlyZeroCase(o, "radiance-0.xml", 4000); });
  add("bad-values", "bad-input", "nan, inf, 1e999, sampleCount 0/-4/2^32/3.5 rejected; -0 read as 0",
      badValues);
  add("degenerate-mesh", "degenerate-geometry",
      "zero-area and repeated-vertex triangles, a mesh without normals", degenerateMesh);
  add("camera-fov-0-180", "bad-input", "camera fov 0 and 180 rejected", cameraFov);
  add("film-1e6-samples", "accumulation", "10^6 samples in one pixel without drift", accumulation);
  return v;
}

}  // namespace

CaseResult checkRejected(const CaseOptions& o, const std::string& file, const std::string& expectedMessage) {
  CaseResult r = exact(1.0, 0.0);
  try {
    load(o, file);
    r.failures.push_back(file + " was accepted");
  } catch (const Error& e) {
    std::string msg = e.what();
    // "…/file.xml:LINE: message"
    size_t at = msg.find(file + ":");
    bool hasLine = at != std::string::npos && at + file.size() + 1 < msg.size() &&
                   std::isdigit(static_cast<unsigned char>(msg[at + file.size() + 1]));
    if (!hasLine)
      r.failures.push_back(file + ": message has no file:line: " + msg);
    else if (msg.find(expectedMessage) == std::string::npos)
      r.failures.push_back(file + ": expected \"" + expectedMessage + "\", got: " + msg);
    else
      r.estimate = 1.0;
  }
  return r;
}

const std::vector<StiffCase>& stiffCases() {
  static const std::vector<StiffCase> cases = makeCases();
  return cases;
}

CaseResult runStiffCase(const StiffCase& c, const CaseOptions& options) {
  try {
    return c.run(options);
  } catch (const std::exception& e) {
    CaseResult r;
    r.failures.push_back(std::string("exception: ") + e.what());
    return r;
  }
}

}  // namespace penumbra::analysis
