#include "core/lights/mesh_lights.h"

#include <algorithm>
#include <unordered_map>

namespace penumbra {
namespace {

uint64_t edgeKey(uint32_t from, uint32_t to) {
  return (uint64_t(from) << 32) | to;
}

// Whether a, e, b, c (counter-clockwise) is a parallelogram: its diagonals a–b and e–c bisect each
// other, to a few float ulps of the coordinates (well inside the distance by which shadow rays stop
// short of a light, so a point sampled on the parallelogram is never behind its own triangles).
bool isParallelogram(const Vec3& a, const Vec3& e, const Vec3& b, const Vec3& c) {
  const float scale =
      std::max({maxAbsComponent(a), maxAbsComponent(b), maxAbsComponent(c), maxAbsComponent(e)});
  return maxAbsComponent((a + b) - (e + c)) <= 0x1p-21f * scale;
}

}  // namespace

MeshLightStats addMeshLights(const TriangleMesh& mesh, const Color3& radiance,
                             std::vector<PolygonLight>& lights, std::vector<int32_t>& lightOfPrim) {
  MeshLightStats stats;
  const size_t count = mesh.triangles.size();
  const size_t base = lightOfPrim.size();
  lightOfPrim.resize(base + count, -1);
  auto corner = [&](size_t tri, int k) { return mesh.positions[mesh.triangles[tri][k % 3]]; };
  auto vertexIndex = [&](size_t tri, int k) { return mesh.triangles[tri][k % 3]; };
  auto triangleLight = [&](size_t tri) {
    const Vec3 a = corner(tri, 0);
    return PolygonLight::make(a, corner(tri, 1) - a, corner(tri, 2) - a, false, radiance);
  };

  // Directed edges of the triangles that can emit; a triangle's edge a -> b meets its neighbour's b -> a.
  std::vector<bool> valid(count);
  std::unordered_map<uint64_t, uint32_t> edges;
  edges.reserve(3 * count);
  for (size_t i = 0; i < count; ++i) {
    valid[i] = triangleLight(i).valid();
    if (!valid[i]) continue;
    for (int k = 0; k < 3; ++k) edges.emplace(edgeKey(vertexIndex(i, k), vertexIndex(i, k + 1)), uint32_t(i));
  }
  std::vector<bool> done(count, false);
  for (size_t i = 0; i < count; ++i) {
    if (!valid[i]) {
      ++stats.degenerate;
      continue;
    }
    if (done[i]) continue;
    done[i] = true;
    PolygonLight light = triangleLight(i);
    size_t partner = count;
    for (int k = 0; k < 3 && partner == count; ++k) {
      const auto it = edges.find(edgeKey(vertexIndex(i, k + 1), vertexIndex(i, k)));
      if (it == edges.end() || done[it->second]) continue;
      const size_t j = it->second;
      // Triangle i is a -> b -> c, triangle j is b -> a -> e: the quad a, e, b, c.
      const Vec3 a = corner(i, k), b = corner(i, k + 1), c = corner(i, k + 2);
      Vec3 e(0.f);
      for (int m = 0; m < 3; ++m)
        if (vertexIndex(j, m) == vertexIndex(i, k + 1) && vertexIndex(j, m + 1) == vertexIndex(i, k))
          e = corner(j, m + 2);
      if (!isParallelogram(a, e, b, c)) continue;
      const PolygonLight quad = PolygonLight::make(a, e - a, c - a, true, radiance);
      if (!quad.valid()) continue;
      light = quad;
      partner = j;
    }
    const auto index = static_cast<int32_t>(lights.size());
    lights.push_back(light);
    ++stats.lights;
    lightOfPrim[base + i] = index;
    if (partner < count) {
      done[partner] = true;
      lightOfPrim[base + partner] = index;
      stats.paired += 2;
    }
  }
  return stats;
}

}  // namespace penumbra
