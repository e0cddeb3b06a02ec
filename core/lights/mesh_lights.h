// The polygon lights of an emitting triangle mesh: one per triangle, except that two triangles sharing
// an edge (with opposite windings) that together form a parallelogram become one parallelogram light,
// sampled as a whole (a quad light made of two triangles, a `rectangle`, a grid's cells).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/geometry/triangle_mesh.h"
#include "core/lights/polygon_light.h"

namespace penumbra {

struct MeshLightStats {
  size_t lights = 0;      // polygon lights added
  size_t paired = 0;      // triangles merged into parallelograms (two per parallelogram)
  size_t degenerate = 0;  // triangles with no area (or non-finite), which emit nothing
};

// Appends the mesh's lights to `lights` and, per triangle, the index of its light (-1 for a degenerate
// triangle) to `lightOfPrim`. Linear in the mesh's size (edges are matched through a hash table).
MeshLightStats addMeshLights(const TriangleMesh& mesh, const Color3& radiance,
                             std::vector<PolygonLight>& lights, std::vector<int32_t>& lightOfPrim);

}  // namespace penumbra
