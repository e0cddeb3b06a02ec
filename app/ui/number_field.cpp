#include "app/ui/number_field.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/materials/bsdf.h"
#include "core/scene/scene_builder.h"

namespace penumbra::ui {

namespace fields {
const NumberField kSampleCount{"sampleCount", 1, double(kMaxSampleCount), true, "", 0};
const NumberField kSeed{"seed", 0,  9007199254740992.0,
                        true,   "", 0};  // 2^53: every seed up to it is exact here
const NumberField kTargetSpp{"target spp", 0, double(1 << 30), true, "", 0};
const NumberField kSeconds{"time budget", 0.1, 604800, false, " s", 1};
const NumberField kShadingSamples{"shading samples", 1, double(kMaxShadingSamples), true, "", 0};
const NumberField kFov{"fov", 1, 179, false, " deg", 1};
const NumberField kExposure{"exposure", -20, 20, false, " stops", 2};
const NumberField kZoomStops{"zoom", -4, 4, false, " stops", 2};
const NumberField kDividerPercent{"divider", 0, 100, false, " %", 0};
const NumberField kAlpha{"alpha", kMinAlpha, kMaxAlpha, false, "", -4};
const NumberField kReflectance{"kd", 0, 1, false, "", 3};
}  // namespace fields

NumberField shadingSamplesField(std::string_view name) {
  NumberField f = fields::kShadingSamples;
  f.name = name;
  return f;
}

std::string formatNumber(double value, const NumberField& field) {
  char buf[64];
  if (field.integer)
    std::snprintf(buf, sizeof buf, "%.0f", value);
  else if (field.decimals < 0)
    std::snprintf(buf, sizeof buf, "%.*g", -field.decimals, value);
  else
    std::snprintf(buf, sizeof buf, "%.*f", field.decimals, value);
  return buf;
}

namespace {

std::string withUnit(double value, const NumberField& field) {
  return formatNumber(value, field) + std::string(field.unit);
}

}  // namespace

NumberEntry clampNumber(double value, const NumberField& field, double current) {
  NumberEntry e;
  if (std::isnan(value)) {
    e.note = "not a number: kept " + withUnit(current, field);
    return e;
  }
  const std::string name(field.name);
  if (value > field.max) {
    e.value = field.max;
    e.note = "clamped to " + withUnit(field.max, field) + " (the largest " + name + ")";
  } else if (value < field.min) {
    e.value = field.min;
    e.note = "clamped to " + withUnit(field.min, field) + " (the smallest " + name + ")";
  } else if (field.integer && value != std::round(value)) {
    e.value = std::round(value);
    e.note = "rounded to " + withUnit(*e.value, field) + " (" + name + " is a whole number)";
  } else {
    e.value = value;
  }
  return e;
}

NumberEntry parseNumberEntry(std::string_view text, const NumberField& field, double current) {
  const size_t first = text.find_first_not_of(" \t");
  const size_t last = text.find_last_not_of(" \t");
  const std::string trimmed =
      first == std::string_view::npos ? "" : std::string(text.substr(first, last - first + 1));
  // strtod reads every spelling a user types (3000000000, 1e30, -5, 2.5); out of double's range it
  // gives ±HUGE_VAL, which clamps like any large value.
  char* end = nullptr;
  errno = 0;
  const double v = trimmed.empty() ? NAN : std::strtod(trimmed.c_str(), &end);
  if (trimmed.empty() || end != trimmed.c_str() + trimmed.size() || std::isnan(v)) {
    NumberEntry e;
    e.note = "\"" + trimmed + "\" is not a number: kept " + withUnit(current, field);
    return e;
  }
  return clampNumber(v, field, current);
}

}  // namespace penumbra::ui
