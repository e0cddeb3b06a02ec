// The stiff-case catalogue: every sampler, pdf and estimator checked where naive code
// breaks, against closed forms (core/analysis/closed_forms.h) or exact expectations. Run by
// `penumbra check` and by core/analysis/stiff_cases_test.cpp; explained in docs/stiff-cases.md.
//
// A case computes an expected value and an estimate ± standard error and counts NaN / Inf /
// negative samples. It passes iff
//   bad == 0, no invariant failed (e.g. an expected error message), and
//   |estimate − expected| ≤ 4·SE + absSlack + relSlack·|expected|      (z-score ≤ 4 up to slack)
// Deterministic cases have SE = 0 and rely on the (tiny) slack. Cases that group several checks
// report the sub-check with the largest z-score and accumulate bad counts and failures.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace penumbra::analysis {

struct CaseOptions {
  uint64_t seed = 1;
  bool quick = false;    // fewer samples (a smoke run: the z-test still applies)
  std::string sceneDir;  // scenes/stiff; empty: defaultStiffSceneDir()
};

struct CaseResult {
  double expected = 0, estimate = 0, standardError = 0;
  uint64_t bad = 0;         // NaN / Inf / negative samples (or values that must be finite and >= 0)
  double absSlack = 0;      // absolute tolerance for deterministic cases (float rounding)
  double relSlack = 1e-5;   // relative tolerance (float rounding of Le·cos/pdf when SE ≈ 0)
  bool statistical = true;  // false: only bad == 0 and no failures are required (finite-only checks)
  std::vector<std::string> failures;  // violated invariants, each a readable sentence
  std::string note;                   // what was compared (sub-checks)

  double tolerance() const;
  // |estimate − expected| / SE; 0 when within slack, +inf when SE = 0 and outside slack.
  double zScore() const;
  bool passed() const;
};

struct StiffCase {
  std::string name;
  std::string category;  // what the case stresses: one of kStiffCaseCategories
  std::string description;
  std::function<CaseResult(const CaseOptions&)> run;
};

// What the cases stress, in catalogue order; every category has at least one case.
inline constexpr std::array<const char*, 15> kStiffCaseCategories = {
    "warp-extremes",        // warps and samplers at the edges of [0,1)^2
    "narrow-cone",          // solid-angle sampling of lights subtending sin^2 theta_max down to 1e-12
    "tiny-light",           // lights of radius 0 or so small that r^2 underflows
    "near-light",           // shading points on, just outside or inside a light
    "horizon",              // lights below, straddling, centred on or grazing the horizon
    "polygon-light",        // rectangle lights: tiny, sliver, straddling, grazing, huge, in plane, behind
    "glossy",               // microfacet BSDFs: near mirror, very rough, grazing, horizon, kd 0 and 1, IOR 1
    "equal-power",          // the same power from lights of radius 1 down to 1e-6
    "scale",                // the same scene scaled by 1e-4 and 1e4
    "contact",              // ambient occlusion next to a contact point
    "far-side",             // area samples on the light's far side
    "radiance-extremes",    // radiance 0 and 1e6
    "bad-input",            // values a scene must be rejected for, with file and line
    "degenerate-geometry",  // zero-area and repeated-vertex triangles, meshes without normals
    "accumulation",         // 10^6 samples in one pixel
};

// All cases, grouped by category in the order above.
const std::vector<StiffCase>& stiffCases();
// Runs one case, turning an unexpected exception into a failed result.
CaseResult runStiffCase(const StiffCase& c, const CaseOptions& options);

// scenes/stiff: $PENUMBRA_STIFF_SCENES, else ./scenes/stiff if it exists, else the source tree's.
std::string defaultStiffSceneDir();

// Exposed for the test of the test: loads `file` (relative to the scene directory) and requires a
// penumbra::Error whose message contains "file:LINE" and `expectedMessage`.
CaseResult checkRejected(const CaseOptions& options, const std::string& file,
                         const std::string& expectedMessage);

}  // namespace penumbra::analysis
