// The stiff cases of whole renders, contact points, the far side, extreme radiance, bad input and
// the film (the catalogue: stiff_cases.cpp; explained in
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

// ---- 9: scale invariance ------------------------------------------------------------------------------

namespace {

struct Render {
  Image mean, se;
  uint64_t bad = 0;
};

// The scene's own integrator, or `strategy` when given.
Render render(const LoadedScene& s, uint32_t spp, uint64_t seed,
              std::optional<IntegratorDesc> strategy = {}) {
  RenderSettings settings = s.settings;
  settings.seed = seed;
  if (strategy) settings.integrator = withCountsOf(*strategy, settings.integrator);
  RenderLimits limits;
  limits.targetSpp = spp;
  auto job = std::make_shared<const RenderJob>(s.scene, settings, limits);
  Engine engine;
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

}  // namespace

CaseResult scaleCase(const CaseOptions& o, const std::string& kind, std::optional<IntegratorDesc> strategy) {
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
    CaseResult sub =
        fromEstimate(estimate(aoBy(HemisphereWarp::Cosine), *s.scene, ray, count(o, 60000), o.seed),
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
    CaseResult sub =
        fromEstimate(estimate(aoBy(HemisphereWarp::Cosine), *s.scene, ray, count(o, 60000), o.seed),
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
  merge(acc, fromEstimate(estimate(directByLight(LightMeasure::SolidAngle), scene, ray, n, o.seed), truth),
        nameOf(directByLight(LightMeasure::SolidAngle)), first);
  merge(acc, fromEstimate(estimate(directByLight(LightMeasure::Area), scene, ray, n, o.seed + 1), truth),
        nameOf(directByLight(LightMeasure::Area)), first);
  // Hemisphere sampling finds the visible ring with probability ~2e-4: 400k samples (~80 hits) even
  // in --quick, so the standard error is itself estimated well enough for a z-test.
  merge(acc,
        fromEstimate(estimate(directByHemisphere(HemisphereWarp::Cosine), scene, ray, 400000, o.seed + 2),
                     truth),
        nameOf(directByHemisphere(HemisphereWarp::Cosine)), first);
  // MIS: the light samples carry the estimate; a cosine direction that finds the visible ring weighs
  // 1e6 by a weight near 0.
  for (unsigned i = 0; i < std::size(kMisRows); ++i)
    merge(acc, fromEstimate(estimate(kMisRows[i], scene, ray, n, o.seed + 3 + i), truth), nameOf(kMisRows[i]),
          first);
  return acc;
}

// ---- 13, 14: values the builder must reject -------------------------------------------------------------

namespace {

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

}  // namespace

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

CaseResult badBsdfValues(const CaseOptions& o) {
  return rejectAll(
      o, {{"bad-bsdf-alpha-0.xml", "alpha (the roughness) must be in [1e-06, 1000], got 0"},
          {"bad-bsdf-alpha-nan.xml", "expected a finite number, got \"nan\""},
          {"bad-bsdf-alpha-negative.xml", "alpha (the roughness) must be in [1e-06, 1000], got -0.1"},
          {"bad-bsdf-intIOR-0.xml", "intIOR (an index of refraction) must be finite and > 0, got 0"},
          {"bad-bsdf-extIOR-negative.xml", "extIOR (an index of refraction) must be finite and > 0, got -1"},
          {"bad-bsdf-kd-1.5.xml", "kd must have every channel in [0, 1], got 1.5, 0.5, 0.5"},
          {"bad-bsdf-kd-nan.xml", "expected a color like \"1, 0.5, 0\" or a grey value, got \"nan\""},
          {"bad-bsdf-distribution.xml", "unknown distribution \"phong\" (expected one of: beckmann, ggx)"}});
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

}  // namespace penumbra::analysis::kit
