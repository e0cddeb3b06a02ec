// Ways of choosing one area light (a sphere or a polygon) per shading sample, so that the cost of a sample
// does not grow with the number of lights: uniform, proportional to emitted power (alias table), and a light
// BVH (light_bvh.h). Each is a plain struct with the same two queries, so an integrator takes the selection
// as a template parameter (no virtual call):
//   LightPick pick(const Vec3& p, const Vec3& n, double u) const;  // a light and its probability
//   double pmf(const Vec3& p, const Vec3& n, uint32_t light) const;  // the probability pick gives it
// p is the shading point and n its unit shading normal (zero: no normal). pick's pmf == 0 means
// nothing was picked (no lights, or none can reach p): the estimator adds 0.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/geometry/bounds.h"
#include "core/lights/alias_table.h"
#include "core/lights/polygon_light.h"
#include "core/lights/sphere_light.h"

namespace penumbra {

struct LightPick {
  uint32_t light = 0;
  double pmf = 0.0;
};

// Emitted power of a one-sided diffuse sphere (radiant exitance π·L over area 4π r²), from the mean
// of the radiance's channels: 0 exactly when the light cannot contribute.
double sphereLightPower(const SphereLight& light);

// What the selections know of one area light: where it is, its power and which way it emits (the
// cone of its surface normals, pbrt-v4's LightBounds: a sphere emits every way, a polygon along n).
// The selections index lights in the order of the summaries they are built from.
struct LightSummary {
  Bounds box;
  Vec3 centroid{0.f};
  double power = 0.0;
  Vec3 coneAxis{0.f, 0.f, 1.f};
  float cosConeAngle = -1.f;  // cos of the normal cone's half-angle: -1 every direction, 1 only the axis
};
LightSummary summarizeLight(const SphereLight& light);
LightSummary summarizeLight(const PolygonLight& light);
std::vector<LightSummary> summarizeLights(std::span<const SphereLight> lights);

struct UniformLightSelection {
  uint32_t count = 0;

  LightPick pick(const Vec3& /*p*/, const Vec3& /*n*/, double u) const {
    if (count == 0) return {};
    uint32_t i = static_cast<uint32_t>(u * double(count));
    return {i < count ? i : count - 1, 1.0 / double(count)};
  }
  double pmf(const Vec3& /*p*/, const Vec3& /*n*/, uint32_t /*light*/) const {
    return count > 0 ? 1.0 / double(count) : 0.0;
  }
};

struct PowerLightSelection {
  AliasTable table;  // over sphereLightPower; uniform when every light has zero power

  LightPick pick(const Vec3& /*p*/, const Vec3& /*n*/, double u) const {
    if (table.size() == 0) return {};
    const uint32_t i = table.sample(u);
    return {i, table.pmf(i)};
  }
  double pmf(const Vec3& /*p*/, const Vec3& /*n*/, uint32_t light) const { return table.pmf(light); }
};

UniformLightSelection makeUniformLightSelection(std::span<const LightSummary> lights);
PowerLightSelection makePowerLightSelection(std::span<const LightSummary> lights);

}  // namespace penumbra
