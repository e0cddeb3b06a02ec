// Triangle mesh data in world space, as loaded from OBJ and transformed by toWorld.
#pragma once

#include <vector>

#include "core/math/vec.h"

namespace penumbra {

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // per vertex, same count as positions; empty when the OBJ has none
  std::vector<glm::uvec3> triangles;
};

}  // namespace penumbra
