#include "core/analysis/stiff_case_kit.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>

#include "core/analysis/closed_forms.h"
#include "core/math/error.h"
#include "core/math/float_util.h"
#include "core/render/engine.h"
#include "core/render/film.h"
#include "core/render/strategy_axes.h"
#include "core/render/strategy_dispatch.h"
#include "core/sampling/sampler.h"
#include "core/sampling/sampler_table.h"
#include "core/sampling/warp.h"

namespace penumbra::analysis::kit {

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

CaseResult exact(double expected, double estimate, uint64_t bad, double absSlack) {
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

// Reflected radiance Lr of the albedo-1 receiver at x (normal n) lit by every area light (unoccluded).
double directTruth(const Scene& scene, const Vec3& x, const Vec3& n) {
  double sum = 0;
  for (const SphereLight& l : scene.sphereLights)
    sum += double(l.radiance.x) / kPiD *
           sphereLightIrradianceFactor(glm::dvec3(x), glm::dvec3(n), glm::dvec3(l.sphere.center),
                                       double(l.sphere.radius));
  for (const PolygonLight& l : scene.polygonLights)
    sum += double(l.radiance.x) / kPiD * polygonLightIrradianceFactor(l, glm::dvec3(x), glm::dvec3(n));
  return sum;
}

Estimate estimate(const IntegratorDesc& s, const Scene& scene, const Ray& ray, int n, uint64_t seed) {
  return estimateRayOf(withSamples(s, 1), scene, ray, n, seed, SamplerKind::Independent);
}

std::string nameOf(const IntegratorDesc& s) {
  return strategyShortName(s);
}

// Direct lighting of the receiver point by each strategy in `strategies`: light sampling first, then
// hemisphere sampling (which needs no area light) with hemisphereFactor times the samples, then the
// mis strategies with misSamples (0: n); the i-th strategy of that order uses seed + i.
CaseResult directCase(const CaseOptions& o, const std::string& file, unsigned strategies, int n,
                      const Vec3& x, float slope, int hemisphereFactor, int misSamples) {
  LoadedScene s = load(o, file);
  const Scene& scene = *s.scene;
  Ray ray = shallowRayOnto(x, slope);
  CaseResult acc;
  SurfaceHit hit;
  if (!scene.geometry.intersect(ray, hit) || scene.materials[hit.objectId].emits()) {
    acc.failures.push_back("the camera ray does not reach the receiver");
    return acc;
  }
  // The truth at the point the integrator actually shades (float rounding of the hit point matters
  // for receivers 1e-6 r from a light).
  double truth = directTruth(scene, hit.p);
  bool first = true;
  n = count(o, n);
  for (unsigned i = 0; i < std::size(kDirectCaseOrder); ++i) {
    const IntegratorDesc& strategy = kDirectCaseOrder[i];
    if (!(strategies & (1u << i))) continue;
    const int samples = strategy.usesMisAxes() && misSamples > 0       ? misSamples
                        : sceneNeed(strategy) == SceneNeed::AreaLights ? n
                                                                       : hemisphereFactor * n;
    merge(acc, fromEstimate(estimate(strategy, scene, ray, samples, o.seed + i), truth), nameOf(strategy),
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

}  // namespace penumbra::analysis::kit
