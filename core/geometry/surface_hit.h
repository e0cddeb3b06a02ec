// What a ray hit: distance, position, normals and the caller's id of the object.
#pragma once

#include <cstdint>

#include "core/math/vec.h"

namespace penumbra {

struct SurfaceHit {
  float t = 0.f;  // ray parameter of the hit (a distance when the ray's d is unit length)
  Vec3 p{0.f};    // hit point: re-projected onto the sphere / interpolated from the triangle's vertices
  Vec3 ng{0.f};   // geometric normal, unit: outward for spheres, by counter-clockwise winding for triangles
  Vec3 ns{0.f};   // shading normal, unit: interpolated vertex normals if the mesh has them, else ng
  // Magnitude of the coordinates that produced p (max of |p|_inf and the shape's own coordinates);
  // pass it to offsetRayOrigin so that offsets are relative, never a fixed epsilon.
  float offsetScale = 0.f;
  uint32_t objectId = 0;  // the id given to addSphere / addMesh
  uint32_t primId = 0;    // triangle index within its mesh (0 for spheres)
};

}  // namespace penumbra
