// A scene as the packet kernels read it (packet_kernels.cpp): flat arrays of spheres, parallelograms,
// per-object materials and lights, copied once per render from a Scene the packet path
// supports (or, for geometry in a BVH, the Scene whose SceneGeometry the kernels query). Plain data only, so
// the kernels (compiled once per instruction set) include nothing that another translation unit could inline
// with other flags.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry/parallelogram.h"
#include "core/lights/light_selection.h"
#include "core/lights/polygon_light.h"
#include "core/render/render_job.h"

namespace penumbra {

struct PacketSphere {
  float center[3];
  float radius;
  float offsetScale;  // maxAbsComponent(center) + radius: the floor of its hits' offset scale
  uint32_t object;    // index into PacketScene::objects
};

struct PacketQuad {
  Parallelogram shape;
  uint32_t object;
  int32_t polygonLight;  // the polygon light both its triangles are (index into PacketScene::polygons), or -1
};

// What a camera ray finds at an object: albedo/π (0 for a black albedo: nothing is shaded there), whether
// its BSDF is glossy (evaluated and sampled lane by lane by the scalar BSDF, packet_queries.h) and, for an
// emitting sphere, its radiance towards a viewer on its outer side.
struct PacketObject {
  float albedoOverPi[3];
  bool shades;  // something is reflected: a diffuse albedo that is not black, a glossy BSDF that reflects
  bool glossy;
  bool emitter;  // a sphere or polygon light (SurfaceMaterial::emits)
  bool emits;
  bool radianceNonBlack;
  float radiance[3];
  int32_t light;  // its index in PacketScene::lights when it emits, else -1
};

struct PacketLight {
  float center[3];
  float radius;
  float scale;  // lightScaleOf: how far its shadow rays stop short
  float radiance[3];
  bool black;              // radiance 0: every sample is skipped (its draws are still consumed)
  int32_t geometrySphere;  // its index among PacketScene::spheres (skipped by its own shadow rays)
};

struct PacketPolygonLight {
  float p0[3], e1[3], e2[3], n[3];  // PolygonLight's
  float area;
  float scale;  // lightScaleOf: how far its shadow rays stop short
  bool parallelogram;
  float radiance[3];
  bool skipped;  // radiance 0 or no area: no sample lights anything (its draws are still consumed)
};
// A polygon light as the kernels read it.
PacketPolygonLight packetPolygonLight(const PolygonLight& light);

// The light BVH's nodes (LightBvh::nodes) as the kernels walk them, one array per field: the bounding
// sphere of each node's bounds (centre 0.5 (lo + hi), squared radius 0.25 |hi − lo|², both in double as
// lightBvhImportance forms them), its power, its emission cone (axis, cos of its half-angle), its second
// child (a leaf: its light) and 1 where it is a leaf.
struct PacketLightBvh {
  std::vector<double> centreX, centreY, centreZ, radius2, power;
  std::vector<double> axisX, axisY, axisZ, cosCone;
  std::vector<double> child, leaf;
};

// Uniform or power selection (UniformLightSelection, PowerLightSelection) as one alias table the kernels
// sample in lanes, one array per field of AliasTable::Bin: uniform as bins that each keep their own
// light with probability 1/n, which picks what UniformLightSelection::pick picks, bit for bit.
struct PacketLightTable {
  std::vector<double> keep, alias, pmf;
};
PacketLightTable packetLightTable(const UniformLightSelection& selection);
PacketLightTable packetLightTable(const PowerLightSelection& selection);

struct PacketPointLight {
  float position[3];
  float intensity[3];
  float scale;  // maxAbsComponent(position): how far its shadow rays stop short
};

struct PacketDirectionalLight {
  float direction[3];  // unit, towards the light
  float irradiance[3];
  bool black;
};

// The strategies the packet kernels compute (one kernel each, chosen per render).
enum class PacketKernel : uint8_t {
  LightArea,                         // direct by light sampling, area measure, every light
  LightSolidAngle,                   // direct by light sampling, solid-angle measure, every light
  LightAreaSelected,                 // direct by light sampling, area measure, one light picked per sample
  LightSolidAngleSelected,           // ... solid-angle measure
  LightProjectedSolidAngle,          // direct by light sampling, projected solid angle, every light
  LightProjectedSolidAngleSelected,  // ... one light picked per sample
  HemisphereUniform,                 // direct by uniform hemisphere directions
  HemisphereCosine,                  // direct by cosine hemisphere directions
  Bsdf,                  // direct by the surface's own directions (the cosine hemisphere on diffuse surfaces)
  MisAreaBalance,        // MIS of area light sampling and the surface's directions, balance heuristic
  MisAreaPower,          // ... power heuristic
  MisSolidAngleBalance,  // MIS of solid-angle light sampling and the surface's directions, balance
  MisSolidAnglePower,    // ... power heuristic
  MisProjectedSolidAngleBalance,  // MIS of projected-solid-angle light sampling and the surface's, balance
  MisProjectedSolidAnglePower,    // ... power heuristic
  Simple,                         // point and directional lights only
  AoUniform,                      // ambient occlusion, uniform hemisphere
  AoCosine,                       // ambient occlusion, cosine hemisphere
  Normals,                        // the absolute shading normal
};

// `repeats` sampler requests of `n` stratified draws each (next2D(i, n) for i < n), or of n draws of
// `parts` interleaved requests each (next2D(i, n, k, parts) for i < n, k < parts).
struct DrawRequests {
  int repeats, n;
  int parts = 1;
};

// How many draws `requests` make (each request's repeats × n × parts).
int drawCount(const std::vector<DrawRequests>& requests);

struct PacketScene {
  PacketKernel kernel = PacketKernel::LightArea;
  // The scene this was made from, which answers the kernels' queries lane by lane (packet_queries.h):
  // every ray when its geometry is not all flat spheres and parallelograms
  // (geometryQueried; otherwise the arrays below hold the geometry).
  const Scene* scene = nullptr;
  bool geometryQueried = false;
  // The flat geometry (empty when queried) and every object's material.
  std::vector<PacketSphere> spheres;
  std::vector<PacketQuad> quads;
  std::vector<PacketObject> objects;
  bool anyGlossy = false;           // some object's BSDF is glossy
  std::vector<PacketLight> lights;  // sphere lights
  // Polygon lights (Scene::polygonLights, after the sphere lights in the area lights' order): sampled in
  // lanes by every measure (packet_polygon_techniques-inl.h).
  std::vector<PacketPolygonLight> polygons;
  std::vector<PacketPointLight> pointLights;
  std::vector<PacketDirectionalLight> directionalLights;
  LightSelection selection = LightSelection::All;  // how the *Selected kernels pick their light
  PacketLightBvh lightBvh;                         // with LightSelection::Bvh: the BVH they walk in lanes
  PacketLightTable lightTable;                     // with Uniform or Power: the table they sample in lanes
  int samples = 1;       // shading samples per camera sample (per light, for light sampling of every light)
  int lightSamples = 0;  // MIS: per light
  int bsdfSamples = 0;   // MIS
  float rayLengthBound = 0;  // how far ambient occlusion looks
  // The MIS kernels render MisLightShareIntegrator's channels instead of radiance.
  bool lightShare = false;
  // The sampler draws of one camera sample after the filter's, in the integrator's order.
  std::vector<DrawRequests> draws;
  int drawCount() const;
};

// Whether the kernels query the scene's SceneGeometry for every ray: when its shapes are not all flat
// spheres and parallelograms, or when a polygon light is not one of those parallelograms whole.
bool packetGeometryQueried(const Scene& scene);

// The most shading draws (lights × samples) a packet carries: 1 MB of draws per worker (64 bytes a
// draw). Above it a camera sample's draws would stream through memory instead of cache, and the row
// loop takes one camera sample at a time.
inline constexpr int kMaxPacketDraws = 16384;

// Why no packet kernel computes `job` (empty when one does).
std::string packetUnsupportedReason(const RenderJob& job);
// The packet scene of a job for which packetUnsupportedReason is empty.
PacketScene makePacketScene(const RenderJob& job);

}  // namespace penumbra
