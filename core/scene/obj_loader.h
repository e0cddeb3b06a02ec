// Wavefront OBJ → world-space TriangleMesh (tinyobjloader for the parsing, our own checks for
// indices and coordinates so errors carry the OBJ file:line).
#pragma once

#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/geometry/triangle_mesh.h"

namespace penumbra {

struct ObjLoadStats {
  size_t inputTriangles = 0;          // after triangulating polygons
  size_t droppedDegenerate = 0;       // zero-area or repeated-vertex triangles removed
  bool normalsDropped = false;        // some but not all corners had normals: normals were discarded
  std::vector<std::string> warnings;  // tinyobjloader warnings and the above, as "file: warning: ..."
};

// Loads `path` (already resolved, e.g. with resolveScenePath), triangulates, applies `toWorld` to
// positions and its inverse transpose to normals (normalised; empty if the OBJ has none). Vertices
// are shared where (position, normal) index pairs repeat. Errors:
//   missing file     → Error(sceneFile, sceneLine, "cannot open mesh file '...' (resolved to ...)")
//   bad index, NaN/Inf coordinate, short face → Error(objFile, objLine, ...)
//   no faces / only degenerate faces → Error(objFile, 0, ...)
// Degenerate triangles are dropped and counted in stats->droppedDegenerate.
TriangleMesh loadObjMesh(const std::string& path, const glm::mat4& toWorld, const std::string& sceneFile,
                         int sceneLine, ObjLoadStats* stats = nullptr);

}  // namespace penumbra
