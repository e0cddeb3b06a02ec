// Occlusion queries answered together. Each ray is first tested against the geometry outside the BVH
// (the flat loops); the rays that reach the BVH go to Embree as one stream (rtcOccluded1M), which
// traverses a row's incoherent AO rays about 20 % faster than one rtcOccluded1 call per ray
// (bench/yardstick_ao_bench.cpp). Every answer equals SceneGeometry::occluded(ray) for the same ray.
// One batch per thread; clear() keeps its memory, so a batch reused row after row allocates nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/geometry/ray.h"
#include "core/geometry/scene_geometry.h"

namespace penumbra {

class OcclusionBatch {
 public:
  explicit OcclusionBatch(const SceneGeometry& geometry);
  ~OcclusionBatch();
  OcclusionBatch(const OcclusionBatch&) = delete;
  OcclusionBatch& operator=(const OcclusionBatch&) = delete;

  void clear();
  // Queues ray number size() (its answer is occluded(size() - 1) after trace()).
  void add(const Ray& ray);
  // Answers every query added since clear().
  void trace();
  bool occluded(size_t i) const { return blocked_[i] != 0; }
  size_t size() const { return blocked_.size(); }

 private:
  const SceneGeometry& geometry_;
  std::vector<uint8_t> blocked_;
  std::vector<uint32_t> bvhQuery_;  // for each ray sent to the BVH, its query number
  struct EmbreeRays;                // Embree's ray records, opaque here
  std::unique_ptr<EmbreeRays> bvhRays_;
};

}  // namespace penumbra
