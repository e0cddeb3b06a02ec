// All the geometry of a scene behind two queries: nearest hit and occlusion. Spheres are tested
// analytically in a flat loop when there are few of them, otherwise as Embree user geometry that calls
// the same robust test; triangles are tested by brute force in a flat array when there are few of
// them (pairs forming a parallelogram, such as a two-triangle floor, as one primitive), otherwise
// through Embree. Whatever goes to Embree shares one BVH (one traversal per query). No virtual calls
// and no allocation per query;
// concurrent const queries are thread-safe once build() has returned.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry/bounds.h"
#include "core/geometry/parallelogram.h"
#include "core/geometry/ray.h"
#include "core/geometry/sphere.h"
#include "core/geometry/surface_hit.h"
#include "core/geometry/triangle.h"
#include "core/geometry/triangle_mesh.h"

struct RTCRayHit;  // Embree's ray and hit record (embree3/rtcore_ray.h), named here only by pointer

namespace penumbra {

enum class AccelMode : uint8_t {
  Auto,        // brute force up to kBruteForceMaxPrimitives flat primitives, Embree above
  BruteForce,  // always the flat loop (tests, tiny scenes)
  Embree,      // always Embree (if there is at least one triangle)
};

// Up to this many flat primitives (parallelograms, and triangles that pair into none) the flat loop
// is used (bench/geometry_bench.cpp, one 2 GHz core, ns/ray):
//   2-sphere + 2-triangle-plane scene: flat 85, Embree for the plane 144 (Embree's fixed cost per call);
//   random overlapping soups (worst case for the loop): triangles N=2 22 vs 31, N=8 50 vs 58, N=16 85
//   vs 71; parallelograms N=4 60 vs 49, N=8 114 vs 55; closed rock mesh, N=20: 309 vs 187.
// The loop costs ~5 ns per triangle and ~14 ns per parallelogram, Embree ~40 ns fixed plus a slow
// log(N). Whole scenes favour the loop more than soups: Veach's MIS scene (6 parallelograms, 4 sphere
// lights) renders 1.35× faster through the loop one sample at a time and 2.7× in packets, whose lanes
// test parallelograms together where Embree takes rays one at a time (docs/performance.md).
inline constexpr size_t kBruteForceMaxPrimitives = 8;

// Up to this many spheres the flat loop is used, above it the spheres go into the BVH
// (bench/geometry_bench.cpp, BM_Spheres*; figures in docs/performance.md).
inline constexpr size_t kBruteForceMaxSpheres = 32;

// The sphere mode that AccelMode::Auto stands for under the environment variable
// PENUMBRA_SPHERE_ACCEL (unset or "auto": Auto; "bvh": Embree; "brute-force": BruteForce), so tests
// and `penumbra check` can force either path on every scene. Throws penumbra::Error on another value.
AccelMode sphereAccelFromEnvironment();

// The instruction set of the kernels Embree traverses with on this machine ("avx512", "avx2", "avx",
// "sse4.2" or "sse2"). Embree's kernels for different instruction sets round ray-triangle hits
// differently, so an image of a scene traced by Embree is bit for bit the same only between machines
// that report the same name here.
std::string embreeKernelIsa();

class SceneGeometry {
 public:
  SceneGeometry() = default;
  SceneGeometry(SceneGeometry&&) noexcept = default;
  SceneGeometry& operator=(SceneGeometry&&) noexcept = default;

  // Returns the sphere's index. objectId is reported back in SurfaceHit::objectId.
  uint32_t addSphere(const Sphere& sphere, uint32_t objectId);
  // The mesh is copied (its vertex normals are needed to shade Embree hits).
  void addMesh(const TriangleMesh& mesh, uint32_t objectId);
  // Prepares the acceleration structure; must be called after the last add and before queries.
  // `mode` decides for triangles, `sphereMode` for spheres (Auto: sphereAccelFromEnvironment(), then
  // kBruteForceMaxSpheres). Both paths find the same sphere hits: the BVH calls Sphere::intersect.
  // Throws penumbra::Error if Embree fails.
  void build(AccelMode mode = AccelMode::Auto, AccelMode sphereMode = AccelMode::Auto);

  // Nearest hit with ray.tMin < t < ray.tMax.
  bool intersect(const Ray& ray, SurfaceHit& hit) const;
  // intersect() of rays[0..n): found[i] = intersect(rays[i], hits[i]), bit for bit unless two surfaces
  // lie within a few ulps of one distance along a ray (coplanar overlaps), where either may be
  // reported. The rays that reach the BVH go to Embree as one stream (rtcIntersect1M) per
  // kIntersectManyRays, told whether they are coherent (camera rays) or not.
  enum class Coherence : uint8_t { Coherent, Incoherent };
  void intersectMany(const Ray* rays, size_t n, SurfaceHit* hits, bool* found,
                     Coherence coherence = Coherence::Coherent) const;
  static constexpr size_t kIntersectManyRays = 64;
  // Whether anything is hit with ray.tMin < t < ray.tMax. Sphere `skipSphere` (an index returned by
  // addSphere) is not tested: a shadow ray towards a point of a convex light that faces the shading
  // point cannot be blocked by that light, and testing it would only add rounding (and cost).
  bool occluded(const Ray& ray, int32_t skipSphere = -1) const;
  // occluded() of rays[0..n) (n <= kOccludedManyRays): blocked[i] = occluded(rays[i], skipSphere) for
  // the rays with active[i]. The rays that reach the BVH go to Embree as one stream (rtcOccluded1M).
  void occludedMany(const Ray* rays, const bool* active, size_t n, int32_t skipSphere, bool* blocked) const;
  static constexpr size_t kOccludedManyRays = 16;

  Bounds bounds() const { return bounds_; }
  size_t sphereCount() const { return spheres_.size(); }
  size_t triangleCount() const { return triangleCount_; }
  // Brute-force path only: triangle pairs intersected as parallelograms.
  size_t parallelogramCount() const { return quads_.size(); }
  // Whether triangles go through Embree.
  bool usesEmbree() const { return scene_ && trianglesInEmbree_; }
  // Whether spheres go through Embree (as user geometry).
  bool spheresUseBvh() const { return scene_ && spheresInEmbree_; }
  const std::vector<Sphere>& spheres() const { return spheres_; }
  const std::vector<TriangleMesh>& meshes() const { return meshes_; }
  // The objectId given with sphere i and with mesh i.
  uint32_t sphereObjectId(size_t i) const { return sphereIds_[i]; }
  uint32_t meshObjectId(size_t i) const { return meshIds_[i]; }
  // Brute-force path only: the parallelograms, and the triangles tested one by one.
  const std::vector<Parallelogram>& parallelograms() const { return quads_; }
  size_t flatTriangleCount() const { return flat_.size(); }

 private:
  friend class OcclusionBatch;  // sends the BVH part of many occlusion queries to Embree at once
  // occluded() outside the BVH: the flat loops of spheres and parallelograms, and of triangles.
  bool occludedByFlatShapes(const Ray& ray, int32_t skipSphere) const;
  bool occludedByFlatTriangles(const Ray& ray) const;
  // Fills quads_ and flat_ from the meshes: triangle pairs forming a parallelogram, the rest alone.
  void pairFlatTriangles();

  struct FlatTriangle {
    Vec3 p0, p1, p2;
    uint32_t mesh, prim;
    TrianglePlane plane;
  };
  // The nearest triangle hit closer than r.tMax, by either path (kept out of intersect's hot loop).
  // Left uninitialised: every query that reports a triangle writes all of it.
  struct TriangleCandidate {
    TriangleIntersection isect;
    uint32_t mesh, prim;
    const FlatTriangle* flat;  // set on the brute-force path (its hit is re-projected)
  };
  // The nearest hit in the Embree scene closer than r.tMax: a triangle (c filled) or a sphere
  // (*sphere set to its index).
  [[gnu::noinline]] bool nearestEmbreeTriangle(const Ray& r, TriangleCandidate& c, int* sphere) const;
  // nearestEmbreeTriangle()'s answer read from Embree's record of the query.
  bool readEmbreeHit(const RTCRayHit& rh, TriangleCandidate& c, int* sphere) const;
  // One ray's nearest hit between intersect()'s steps: outside the BVH first, then Embree's. Trivial
  // to construct (intersectMany keeps a chunk of them on the stack); nearestOutsideBvh sets it.
  struct NearestHit {
    float tMax;  // the nearest hit so far
    int sphere;
    const Parallelogram* quad;
    float quadU, quadV;
    TriangleCandidate tri;
    bool triHit;
  };
  void nearestOutsideBvh(const Ray& ray, NearestHit& n) const;
  // Folds in the BVH's answer (every Embree hit is nearer than the ones outside: it is bounded by r.tMax).
  static void takeBvhAnswer(bool triangle, int bvhSphere, const TriangleCandidate& c, NearestHit& n);
  bool fillNearestHit(const Ray& ray, const NearestHit& n, SurfaceHit& hit) const;
  [[gnu::noinline]] bool nearestFlatTriangle(const Ray& r, TriangleCandidate& c) const;
  // Owners of Embree's reference-counted handles, opaque here so that this header needs no Embree.
  struct ReleaseEmbreeDevice {
    void operator()(void* device) const;  // rtcReleaseDevice
  };
  struct ReleaseEmbreeScene {
    void operator()(void* scene) const;  // rtcReleaseScene
  };

  std::vector<Sphere> spheres_;
  std::vector<uint32_t> sphereIds_;
  std::vector<TriangleMesh> meshes_;
  std::vector<uint32_t> meshIds_;
  std::vector<Parallelogram> quads_;  // brute-force path only
  std::vector<FlatTriangle> flat_;    // brute-force path only: triangles not in a parallelogram
  size_t triangleCount_ = 0;
  Bounds bounds_;
  bool trianglesInEmbree_ = false;
  bool spheresInEmbree_ = false;
  size_t flatSphereCount_ = 0;     // spheres in the flat loops: all of them, or none when in the BVH
  uint32_t sphereGeometryId_ = 0;  // Embree geometry id of the spheres (after the meshes)
  std::unique_ptr<void, ReleaseEmbreeDevice> device_;  // RTCDevice, created only when a BVH is needed
  std::unique_ptr<void, ReleaseEmbreeScene> scene_;    // RTCScene (released first: declared last)
};

}  // namespace penumbra
