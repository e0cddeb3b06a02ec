// Procedural meshes for benchmarks and stand-in scenes (no large files in git). Deterministic.
#pragma once

#include <cstdint>

#include "core/geometry/triangle_mesh.h"

namespace penumbra {

// A lumpy rock around the origin, radius roughly 0.6..1.3: an icosphere subdivided `subdivisions`
// times (20·4^s triangles: s = 7 → 327,680, s = 8 → 1,310,720) with fBm value-noise radial
// displacement plus ridged valleys (crevices, good for AO). Counter-clockwise outward winding,
// smooth per-vertex normals (area-weighted). The same (subdivisions, seed) gives the same mesh.
TriangleMesh makeRockMesh(int subdivisions, uint32_t seed);

// A planar grid of nu × nv quads (2 triangles each) spanning corner + [0,1]·edgeU + [0,1]·edgeV,
// winding so the geometric normal is normalize(cross(edgeU, edgeV)); per-vertex normals included.
TriangleMesh makeGridPlane(const Vec3& corner, const Vec3& edgeU, const Vec3& edgeV, int nu, int nv);

}  // namespace penumbra
