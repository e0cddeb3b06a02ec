// The viewer's numeric fields without ImGui: each field's documented range, and what a typed text
// becomes — a value within the range, and a note saying what was done to it ("clamped to 16777216
// (the largest sampleCount)"), or a refusal when the text is no number. app/ui/number_input.cpp
// draws the fields; the ranges are listed in docs/viewer.md.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace penumbra::ui {

struct NumberField {
  std::string_view name;    // as notes name it: "sampleCount", "time budget"
  double min = 0, max = 0;  // inclusive (integer fields: whole numbers up to 2^53 exactly)
  bool integer = true;
  std::string_view unit;  // appended to values in notes: " s", " deg"
  int decimals = 0;       // float fields: digits shown after the point (negative: significant digits)
};

// The viewer's fields and their ranges (the scene file's where it has one).
namespace fields {
extern const NumberField kSampleCount;     // [1, 2^24] as <sampler sampleCount>
extern const NumberField kSeed;            // [0, 2^53]
extern const NumberField kTargetSpp;       // [0, 2^30] (0: never stop), as `penumbra render --spp`
extern const NumberField kSeconds;         // [0.1, 604800] s (one week)
extern const NumberField kShadingSamples;  // [1, 2^16] as the integrator's sample counts
extern const NumberField kFov;             // [1, 179] degrees
extern const NumberField kExposure;        // [-20, 20] stops
extern const NumberField kZoomStops;       // [-4, 4]: zoom 1/16x to 16x
extern const NumberField kDividerPercent;  // [0, 100]
extern const NumberField kAlpha;           // [1e-6, 1000] as a microfacet BSDF's roughness
extern const NumberField kReflectance;     // [0, 1] as microfacet's kd
}  // namespace fields

// A count field for one of the integrator's sample counts (its own name, kShadingSamples' range).
NumberField shadingSamplesField(std::string_view name);

struct NumberEntry {
  std::optional<double> value;  // empty: the text is no number (the field keeps its value)
  std::string note;             // what was done, or why nothing was; empty when taken as typed
};

// The text typed into `field`: a number within its range (integers rounded to the nearest whole
// number), clamped when outside it; "", "abc" and "nan" are refused with a note naming `current`,
// the value the field keeps.
NumberEntry parseNumberEntry(std::string_view text, const NumberField& field, double current);
// A value from a slider or step button, clamped into the range like a typed one (NaN refused).
NumberEntry clampNumber(double value, const NumberField& field, double current);
// The value as the field shows it ("16777216", "10.0").
std::string formatNumber(double value, const NumberField& field);

}  // namespace penumbra::ui
