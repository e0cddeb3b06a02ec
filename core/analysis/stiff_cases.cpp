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
#include "core/analysis/stiff_case_kit.h"
#include "core/math/error.h"
#include "core/math/float_util.h"
#include "core/render/engine.h"
#include "core/render/film.h"
#include "core/render/strategy_axes.h"
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

using namespace kit;
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
  // Polygon lights (rectangles): light sampling by every measure, MIS and, where the light is large
  // enough for them to find, hemisphere directions.
  const unsigned kLight = kSolid | kProjected | kArea;
  const struct {
    const char* name;
    const char* description;
    unsigned strategies;
  } polygonCases[] = {
      {"polygon-above", "rectangle light above the receiver (all strategies)", kAll},
      {"polygon-tiny", "rectangle 2e-6 across at distance 1 (light sampling, mis)", kLight | kMis},
      {"polygon-sliver", "rectangle of aspect 1e4 (light sampling, mis)", kLight | kMis},
      {"polygon-straddling", "wall light straddling the horizon (all strategies)", kAll},
      {"polygon-grazing", "window light within 0.4 degrees of the horizon (light sampling, mis)",
       kLight | kMis},
      // Area samples of a light 2e4 times wider than its height find the bright spot under it too rarely.
      {"polygon-huge", "rectangle 200 across at height 0.01 (all but area sampling)",
       kSolid | kProjected | kCosine | kUniform | kMis},
  };
  for (const auto& c : polygonCases) {
    const std::string file = std::string(c.name) + ".xml";
    const unsigned strategies = c.strategies;
    add(c.name, "polygon-light", c.description,
        [file, strategies](const CaseOptions& o) { return directCase(o, file, strategies, 20000); });
  }
  add("polygon-in-plane", "polygon-light", "the receiver in the light's plane: exactly 0",
      [](const CaseOptions& o) { return exactlyZeroCase(o, "polygon-in-plane.xml", 4000); });
  add("polygon-back-side", "polygon-light", "the light faces away (one-sided): exactly 0",
      [](const CaseOptions& o) { return exactlyZeroCase(o, "polygon-back-side.xml", 4000); });
  add("glossy-near-mirror", "glossy", "alpha 1e-4, every model at 0, 45 and 80 degrees: draws vs albedo",
      glossyNearMirror);
  add("glossy-rough", "glossy", "alpha 1 and 10, every model: draws vs albedo", glossyRough);
  add("glossy-grazing-89.9", "glossy", "wo 89.9 degrees from the normal, alpha 0.05 and 0.5", glossyGrazing);
  add("glossy-mirror-direction", "glossy", "f and pdf at the exact mirror direction, alpha down to 1e-6",
      glossyMirrorDirection);
  add("glossy-kd-0-1", "glossy", "microfacet kd 0 (specular only) and 1 (diffuse only)", glossyKdZeroAndOne);
  add("glossy-horizon", "glossy", "directions in the surface and 1e-7 above it", glossyHorizon);
  add("glossy-ior-1", "glossy", "intIOR = extIOR: no specular reflection", glossyIorOne);
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
              finiteOnly(estimate(directByHemisphere(HemisphereWarp::Cosine), *s.scene, ray, count(o, 20000),
                                  o.seed)),
              nameOf(directByHemisphere(HemisphereWarp::Cosine)), first);
        merge(r,
              finiteOnly(estimate(directByHemisphere(HemisphereWarp::Uniform), *s.scene, ray, count(o, 20000),
                                  o.seed)),
              nameOf(directByHemisphere(HemisphereWarp::Uniform)), first);
        equalPowerTruths(o, "equal-power-r1e-3.xml", r);
        return r;
      });
  add("scale-ao", "scale", "AO image at scales 1e-4 and 1e4 vs 1",
      [](const CaseOptions& o) { return scaleCase(o, "ao"); });
  add("scale-direct", "scale", "direct image at scales 1e-4 and 1e4 vs 1",
      [](const CaseOptions& o) { return scaleCase(o, "direct"); });
  const std::pair<IntegratorDesc, const char*> misScales[] = {{kMisRows[0], "scale-mis-solid-angle"},
                                                              {kMisRows[3], "scale-mis-area"},
                                                              {kMisRows[4], "scale-mis-projected"}};
  for (const auto& [row, name] : misScales) {
    const IntegratorDesc mis = row;  // a plain copy: clang before 16 cannot capture a structured binding
    add(name, "scale", "direct image at scales 1e-4 and 1e4 vs 1, " + strategyLabel(mis),
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
  add("bad-bsdf-values", "bad-input", "alpha <= 0 or NaN, IOR <= 0, kd outside [0, 1] or NaN rejected",
      badBsdfValues);
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
