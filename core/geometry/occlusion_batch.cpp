#include "core/geometry/occlusion_batch.h"

#include "core/geometry/embree_rays.h"

namespace penumbra {

struct OcclusionBatch::EmbreeRays {
  std::vector<RTCRay> rays;
};

OcclusionBatch::OcclusionBatch(const SceneGeometry& geometry)
    : geometry_(geometry), bvhRays_(std::make_unique<EmbreeRays>()) {}

OcclusionBatch::~OcclusionBatch() = default;

void OcclusionBatch::clear() {
  blocked_.clear();
  bvhQuery_.clear();
  bvhRays_->rays.clear();
}

void OcclusionBatch::add(const Ray& ray) {
  const uint32_t query = uint32_t(blocked_.size());
  // The same tests as SceneGeometry::occluded, the BVH's deferred.
  const bool flat = geometry_.occludedByFlatShapes(ray, -1) || geometry_.occludedByFlatTriangles(ray);
  blocked_.push_back(flat ? 1 : 0);
  if (flat || !geometry_.scene_ || !(ray.tMax > ray.tMin)) return;
  RTCRay& r = bvhRays_->rays.emplace_back();
  setupRay(ray, ray.tMax, r);
  bvhQuery_.push_back(query);
}

void OcclusionBatch::trace() {
  std::vector<RTCRay>& rays = bvhRays_->rays;
  if (rays.empty()) return;
  OcclusionContext context;
  rtcInitIntersectContext(&context.base);
  context.base.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  context.skipSphere = -1;
  rtcOccluded1M(static_cast<RTCScene>(geometry_.scene_.get()), &context.base, rays.data(),
                unsigned(rays.size()), sizeof(RTCRay));
  for (size_t i = 0; i < rays.size(); ++i)
    if (rays[i].tfar < 0.f) blocked_[bvhQuery_[i]] = 1;  // Embree sets tfar = -inf on a hit
}

}  // namespace penumbra
