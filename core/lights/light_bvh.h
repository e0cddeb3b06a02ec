// A BVH over the sphere lights for choosing one light per shading sample by its importance as seen
// from the shading point, in the manner of pbrt-v4's BVHLightSampler (Pharr, Jakob, Humphreys,
// "Physically Based Rendering", 4th ed., sec. 12.6.3; after Conty Estevez & Kulla, "Importance
// Sampling of Many Lights with Adaptive Tree Splitting", HPG 2018). Descending from the root, each
// child is taken with probability proportional to its importance: its power over the squared distance
// to its bounds, times a bound of the receiver's cosine over those bounds, times (for one-sided polygon
// lights) a bound of the emitters' cosine towards p over the cone of their normals (pbrt-v4's
// LightBounds; a node holding a sphere emits every way and skips that factor).
// The importance is conservative: a light that can light p (p in front of it) never gets 0.
// The probabilities of all lights sum to 1 at every p that the root's bounds can reach, else to 0.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/geometry/bounds.h"
#include "core/lights/light_selection.h"

namespace penumbra {

struct LightBvhNode {
  Vec3 lo{0.f}, hi{0.f};         // bounds of the node's lights
  double power = 0.0;            // their total power (every light counts 1 when all have zero power)
  Vec3 coneAxis{0.f, 0.f, 1.f};  // a cone holding the normals of its lights' emitting sides
  float cosConeAngle = -1.f;     // cos of the cone's half-angle (-1: every direction)
  uint32_t child = 0;            // interior: the second child (the first is this node + 1); leaf: the light
  uint32_t parent = 0;           // the root is its own parent
  bool leaf = false;
};

// The importance of a node's bounds and power for a shading point p with unit normal n (zero: none).
double lightBvhImportance(const LightBvhNode& node, const Vec3& p, const Vec3& n);

struct LightBvh {
  std::vector<LightBvhNode> nodes;  // depth first, the root at 0
  std::vector<uint32_t> leafOf;     // per light, its leaf node

  LightPick pick(const Vec3& p, const Vec3& n, double u) const;
  double pmf(const Vec3& p, const Vec3& n, uint32_t light) const;
};

// Binned surface-area-and-power split (pbrt-v4's cost without its orientation term), one light per leaf.
LightBvh makeLightBvh(std::span<const LightSummary> lights);

// The smallest cone (axis, cos of its half-angle) found by joining two cones of directions, as
// pbrt-v4's DirectionCone::Union: the wider one when it holds the other, else the cone spanning both
// (every direction once that passes π).
void joinCones(Vec3& axis, float& cosAngle, const Vec3& otherAxis, float otherCosAngle);

}  // namespace penumbra
