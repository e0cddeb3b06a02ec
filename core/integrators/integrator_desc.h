// Which estimator renders the image, with its settings. Plain data: the viewer edits it live and the
// engine resolves it to one concrete integrator type per pass (no per-sample dispatch).
#pragma once

#include <cstdint>
#include <string>

namespace penumbra {

enum class IntegratorType : uint8_t { Normals, Simple, Ao, Direct };
// How `direct` estimates light from area emitters.
enum class DirectMeasure : uint8_t { Hemisphere, Area, SolidAngle };
// Direction sampling for ao, and for direct with measure = hemisphere.
enum class HemisphereWarp : uint8_t { Uniform, Cosine };

struct IntegratorDesc {
  IntegratorType type = IntegratorType::Direct;
  int samples = 1;  // shading samples per camera sample (ao: shadingSamples, direct: nSamples)
  DirectMeasure measure = DirectMeasure::SolidAngle;
  HemisphereWarp warp = HemisphereWarp::Cosine;
};

const char* integratorTypeName(IntegratorType type);
const char* directMeasureName(DirectMeasure measure);
// The assignment's spelling: uniform-hemisphere / cosine-hemisphere.
const char* hemisphereWarpName(HemisphereWarp warp);
bool parseIntegratorType(const std::string& name, IntegratorType& out);
// Accepts hemisphere | area | solid-angle | solidAngle.
bool parseDirectMeasure(const std::string& name, DirectMeasure& out);
// Accepts uniform | uniform-hemisphere | cosine | cosine-hemisphere.
bool parseHemisphereWarp(const std::string& name, HemisphereWarp& out);

// A short human label, e.g. "direct/solid-angle" or "ao/cosine".
std::string strategyLabel(const IntegratorDesc& desc);

}  // namespace penumbra
