// Penumbra's rays as Embree's, for the .cpp files that call Embree (no header outside them includes
// Embree).
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>

#include "core/geometry/ray.h"

namespace penumbra {

inline void setupRay(const Ray& ray, float tMax, RTCRay& r) {
  r.org_x = ray.o.x;
  r.org_y = ray.o.y;
  r.org_z = ray.o.z;
  r.dir_x = ray.d.x;
  r.dir_y = ray.d.y;
  r.dir_z = ray.d.z;
  r.tnear = ray.tMin;
  r.tfar = tMax;
  r.time = 0.f;
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
}

inline void setupRayHit(const Ray& ray, float tMax, RTCRayHit& rh) {
  setupRay(ray, tMax, rh.ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

// An occlusion query's context: Embree's, followed by the sphere the shadow ray must not test.
struct OcclusionContext {
  RTCIntersectContext base;
  int32_t skipSphere;
};

}  // namespace penumbra
