// Occlusion queries answered together. Each ray is first tested against the geometry outside the BVH
// (the flat loops); the rays that reach the BVH go to Embree as one stream (rtcOccluded1M), which
// traverses a row's incoherent AO rays about 20 % faster than one rtcOccluded1 call per ray
// (bench/yardstick_ao_bench.cpp). Every answer equals SceneGeometry::occluded(ray) for the same ray.
// One batch per thread; clear() keeps its memory, so a batch reused row after row allocates nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/geometry/ray.h"
#include "core/geometry/scene_geometry.h"

namespace penumbra {

class OcclusionBatch {
 public:
  explicit OcclusionBatch(const SceneGeometry& geometry);

  void clear() {
    blocked_.clear();
    bvhQuery_.clear();
    bvhRays_.clear();
  }
  // Queues ray number size() (its answer is occluded(size() - 1) after trace()). Inline: it runs once
  // per AO ray.
  void add(const Ray& ray) {
    const uint32_t query = uint32_t(blocked_.size());
    // The same tests as SceneGeometry::occluded, the BVH's deferred.
    const bool flat = hasFlatGeometry_ &&
                      (geometry_.occludedByFlatShapes(ray, -1) || geometry_.occludedByFlatTriangles(ray));
    blocked_.push_back(flat ? 1 : 0);
    // An empty segment is blocked by nothing (as in occluded()).
    if (flat || !hasBvh_ || !(ray.tMax > ray.tMin)) return;
    bvhRays_.push_back(StreamRay{ray.o.x, ray.o.y, ray.o.z, ray.tMin, ray.d.x, ray.d.y, ray.d.z, 0.f,
                                 ray.tMax, ~0u, 0u, 0u});
    bvhQuery_.push_back(query);
  }
  // Answers every query added since clear().
  void trace();
  bool occluded(size_t i) const { return blocked_[i] != 0; }
  size_t size() const { return blocked_.size(); }

 private:
  // Embree's RTCRay field for field (occlusion_batch.cpp checks the layout against Embree's header),
  // so that a ray is queued here without that header.
  struct alignas(16) StreamRay {
    float orgX, orgY, orgZ, tnear, dirX, dirY, dirZ, time, tfar;
    uint32_t mask, id, flags;
  };

  const SceneGeometry& geometry_;
  bool hasFlatGeometry_;  // spheres, parallelograms or triangles outside the BVH
  bool hasBvh_;
  std::vector<uint8_t> blocked_;
  std::vector<StreamRay> bvhRays_;
  std::vector<uint32_t> bvhQuery_;  // for each ray sent to the BVH, its query number
};

}  // namespace penumbra
