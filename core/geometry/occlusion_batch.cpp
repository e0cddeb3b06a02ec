#include "core/geometry/occlusion_batch.h"

#include <cstddef>

#include "core/geometry/embree_rays.h"

namespace penumbra {

OcclusionBatch::OcclusionBatch(const SceneGeometry& geometry)
    : geometry_(geometry),
      hasFlatGeometry_(geometry.flatSphereCount_ > 0 || !geometry.quads_.empty() || !geometry.flat_.empty()),
      hasBvh_(geometry.scene_ != nullptr) {}

void OcclusionBatch::trace() {
  static_assert(sizeof(StreamRay) == sizeof(RTCRay) && alignof(StreamRay) == alignof(RTCRay));
  static_assert(offsetof(StreamRay, orgX) == offsetof(RTCRay, org_x) &&
                offsetof(StreamRay, tnear) == offsetof(RTCRay, tnear) &&
                offsetof(StreamRay, dirX) == offsetof(RTCRay, dir_x) &&
                offsetof(StreamRay, time) == offsetof(RTCRay, time) &&
                offsetof(StreamRay, tfar) == offsetof(RTCRay, tfar) &&
                offsetof(StreamRay, mask) == offsetof(RTCRay, mask) &&
                offsetof(StreamRay, id) == offsetof(RTCRay, id) &&
                offsetof(StreamRay, flags) == offsetof(RTCRay, flags));
  if (bvhRays_.empty()) return;
  OcclusionContext context;
  rtcInitIntersectContext(&context.base);
  context.base.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  context.skipSphere = -1;
  // Embree, a separate library, reads and writes the records as its RTCRay (the same layout).
  rtcOccluded1M(static_cast<RTCScene>(geometry_.scene_.get()), &context.base,
                reinterpret_cast<RTCRay*>(bvhRays_.data()), unsigned(bvhRays_.size()), sizeof(RTCRay));
  for (size_t i = 0; i < bvhRays_.size(); ++i)
    if (bvhRays_[i].tfar < 0.f) blocked_[bvhQuery_[i]] = 1;  // Embree sets tfar = -inf on a hit
}

}  // namespace penumbra
