// What the stiff cases (stiff_cases.h) are written with: the scene directory and sample counts of a
// run, verdicts from estimates and exact values, the closed form at the plane scenes' receiver, and
// one strategy's estimate along a ray. The case functions themselves are declared at the end; each
// file of cases defines one group of them, and stiff_cases.cpp lists them in catalogue order.
#pragma once

#include <cstdint>
#include <iterator>
#include <optional>
#include <string>

#include "core/analysis/ray_estimate.h"
#include "core/analysis/stiff_cases.h"
#include "core/integrators/integrator_desc.h"
#include "core/math/vec.h"
#include "core/scene/scene_builder.h"

namespace penumbra::analysis::kit {

inline const Vec3 kUp(0.f, 0.f, 1.f);
inline const Vec3 kReceiver(0.31f, 0.17f, 0.f);  // the receiver point of the plane scenes (generate.py: X)

std::string sceneDir(const CaseOptions& o);
LoadedScene load(const CaseOptions& o, const std::string& file);
// n samples, or an eighth of them (at least 1000) in a quick run.
int count(const CaseOptions& o, int n);
std::string num(double v);

// Folds a sub-check into a case: the row shows the sub-check with the largest z-score (a failing one
// first); bad counts and failures accumulate; the note lists every sub-check.
void merge(CaseResult& acc, const CaseResult& sub, const std::string& label, bool& first);
CaseResult fromEstimate(const Estimate& e, double expected);
CaseResult exact(double expected, double estimate, uint64_t bad = 0, double absSlack = 0.0);
CaseResult finiteOnly(const Estimate& e);

// Reflected radiance Lr of the albedo-1 receiver at x (normal n) lit by every sphere light.
double directTruth(const Scene& scene, const Vec3& x, const Vec3& n = kUp);

// One strategy's estimate along `ray`, one shading sample per camera sample.
Estimate estimate(const IntegratorDesc& s, const Scene& scene, const Ray& ray, int n, uint64_t seed);
std::string nameOf(const IntegratorDesc& s);

// The mis strategies: every light measure with both heuristics (one light and one cosine sample each).
inline constexpr IntegratorDesc kMisRows[] = {
    directByMis(LightMeasure::SolidAngle, MisHeuristic::Power),
    directByMis(LightMeasure::SolidAngle, MisHeuristic::Balance),
    directByMis(LightMeasure::Area, MisHeuristic::Power),
    directByMis(LightMeasure::Area, MisHeuristic::Balance),
    directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Power),
    directByMis(LightMeasure::ProjectedSolidAngle, MisHeuristic::Balance)};
// The strategies directCase runs, in its order, and the bit of each in its `strategies` mask.
inline constexpr IntegratorDesc kDirectCaseOrder[] = {directByLight(LightMeasure::SolidAngle),
                                                      directByLight(LightMeasure::Area),
                                                      directByLight(LightMeasure::ProjectedSolidAngle),
                                                      directByHemisphere(HemisphereWarp::Cosine),
                                                      directByHemisphere(HemisphereWarp::Uniform),
                                                      kMisRows[0],
                                                      kMisRows[1],
                                                      kMisRows[2],
                                                      kMisRows[3],
                                                      kMisRows[4],
                                                      kMisRows[5]};
inline constexpr unsigned kSolid = 1u << 0, kArea = 1u << 1, kProjected = 1u << 2, kCosine = 1u << 3,
                          kUniform = 1u << 4, kMis = 0x3fu << 5,
                          kAll = kSolid | kArea | kProjected | kCosine | kUniform | kMis;

// Direct lighting of the receiver point by each strategy in `strategies`: light sampling first, then
// hemisphere sampling (which needs no area light) with hemisphereFactor times the samples, then the
// mis strategies with misSamples (0: n); the i-th strategy of that order uses seed + i.
CaseResult directCase(const CaseOptions& o, const std::string& file, unsigned strategies, int n,
                      const Vec3& x = kReceiver, float slope = 1e-4f, int hemisphereFactor = 4,
                      int misSamples = 0);
// A case whose answer is exactly 0 for every strategy (no slack: 0 must come out as 0).
CaseResult exactlyZeroCase(const CaseOptions& o, const std::string& file, int n);

// ---- the cases: stiff_cases_sampling.cpp (warps, samplers, tiny and near lights) -----------------
CaseResult warpExtremes(const CaseOptions& o);
CaseResult diskAndCosineRim(const CaseOptions& o);
CaseResult coneCase(const CaseOptions& o, const std::string& tag);  // cone-sin2-TAG.xml
CaseResult radiusZero(const CaseOptions& o);
CaseResult sin2Underflow(const CaseOptions& o);
CaseResult onSurface(const CaseOptions& o);
CaseResult outside1e8(const CaseOptions& o);
CaseResult inside(const CaseOptions& o);

// ---- stiff_cases_images.cpp (whole renders, contact, far side, extremes, bad input, the film) ----
// kind "ao" or "direct"; the scene's own strategy, or `strategy` when given.
CaseResult scaleCase(const CaseOptions& o, const std::string& kind,
                     std::optional<IntegratorDesc> strategy = {});
CaseResult aoOnSphereNearContact(const CaseOptions& o);
CaseResult aoOnPlaneNearContact(const CaseOptions& o);
CaseResult areaFarSide(const CaseOptions& o);
CaseResult brightOccluded(const CaseOptions& o);
CaseResult badValues(const CaseOptions& o);
CaseResult degenerateMesh(const CaseOptions& o);
CaseResult cameraFov(const CaseOptions& o);
CaseResult accumulation(const CaseOptions& o);
CaseResult badBsdfValues(const CaseOptions& o);

// ---- stiff_cases_glossy.cpp (the reflection models' extremes) ------------------------------------
CaseResult glossyNearMirror(const CaseOptions& o);
CaseResult glossyRough(const CaseOptions& o);
CaseResult glossyGrazing(const CaseOptions& o);
CaseResult glossyMirrorDirection(const CaseOptions& o);
CaseResult glossyKdZeroAndOne(const CaseOptions& o);
CaseResult glossyHorizon(const CaseOptions& o);
CaseResult glossyIorOne(const CaseOptions& o);

}  // namespace penumbra::analysis::kit
