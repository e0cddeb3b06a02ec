#include "core/geometry/procedural_mesh.h"

#include <cmath>
#include <unordered_map>

#include "core/math/error.h"

namespace penumbra {
namespace {

uint32_t hash3(int x, int y, int z, uint32_t seed) {
  uint32_t h = seed * 0x9E3779B9u;
  h ^= static_cast<uint32_t>(x) * 0x85EBCA6Bu;
  h = (h ^ (h >> 13)) * 0xC2B2AE35u;
  h ^= static_cast<uint32_t>(y) * 0x27D4EB2Fu;
  h = (h ^ (h >> 15)) * 0x165667B1u;
  h ^= static_cast<uint32_t>(z) * 0x9E3779B1u;
  h = (h ^ (h >> 16)) * 0x85EBCA6Bu;
  return h ^ (h >> 13);
}

// Value noise in [0, 1], C2-smooth (quintic fade).
float valueNoise(const Vec3& p, uint32_t seed) {
  const Vec3 f = glm::floor(p);
  const int x = static_cast<int>(f.x), y = static_cast<int>(f.y), z = static_cast<int>(f.z);
  const Vec3 u = p - f;
  const Vec3 w = u * u * u * (u * (u * 6.f - 15.f) + 10.f);
  auto v = [&](int dx, int dy, int dz) {
    return static_cast<float>(hash3(x + dx, y + dy, z + dz, seed) >> 8) * (1.f / 16777216.f);
  };
  const float x00 = glm::mix(v(0, 0, 0), v(1, 0, 0), w.x), x10 = glm::mix(v(0, 1, 0), v(1, 1, 0), w.x);
  const float x01 = glm::mix(v(0, 0, 1), v(1, 0, 1), w.x), x11 = glm::mix(v(0, 1, 1), v(1, 1, 1), w.x);
  return glm::mix(glm::mix(x00, x10, w.y), glm::mix(x01, x11, w.y), w.z);
}

// fBm in roughly [-1, 1].
float fbm(Vec3 p, uint32_t seed, int octaves) {
  float sum = 0.f, amp = 0.5f, norm = 0.f;
  for (int i = 0; i < octaves; ++i) {
    sum += amp * (2.f * valueNoise(p, seed + 101u * i) - 1.f);
    norm += amp;
    amp *= 0.5f;
    p = p * 2.03f + Vec3(17.1f, -3.7f, 9.3f);
  }
  return sum / norm;
}

float rockRadius(const Vec3& dir, uint32_t seed) {
  const float lumps = fbm(dir * 1.6f, seed, 5);
  // Ridged noise: 1 at the noise's mid-level, producing narrow valleys (crevices) along it.
  const float ridge = 1.f - std::abs(2.f * valueNoise(dir * 3.1f + Vec3(5.f), seed ^ 0xA5A5u) - 1.f);
  return 1.f + 0.3f * lumps - 0.18f * ridge * ridge * ridge * ridge;
}

void computeVertexNormals(TriangleMesh& mesh) {
  mesh.normals.assign(mesh.positions.size(), Vec3(0.f));
  for (const glm::uvec3& t : mesh.triangles) {
    const Vec3 n = glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                              mesh.positions[t.z] - mesh.positions[t.x]);  // area-weighted
    mesh.normals[t.x] += n;
    mesh.normals[t.y] += n;
    mesh.normals[t.z] += n;
  }
  for (Vec3& n : mesh.normals) {
    const float l = glm::length(n);
    n = l > 0.f ? n / l : Vec3(0, 0, 1);
  }
}

}  // namespace

TriangleMesh makeRockMesh(int subdivisions, uint32_t seed) {
  if (subdivisions < 0 || subdivisions > 10) throw Error("rock mesh: subdivisions must be in [0, 10]");
  const float g = (1.f + std::sqrt(5.f)) * 0.5f;
  std::vector<Vec3> pos = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                           {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  for (Vec3& p : pos) p = glm::normalize(p);
  std::vector<glm::uvec3> tris = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                  {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                  {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                  {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::unordered_map<uint64_t, uint32_t> midpoints;
    midpoints.reserve(tris.size() * 2);
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const uint64_t key = a < b ? (uint64_t(a) << 32 | b) : (uint64_t(b) << 32 | a);
      auto [it, inserted] = midpoints.try_emplace(key, static_cast<uint32_t>(pos.size()));
      if (inserted) pos.push_back(glm::normalize(pos[a] + pos[b]));
      return it->second;
    };
    std::vector<glm::uvec3> next;
    next.reserve(tris.size() * 4);
    for (const glm::uvec3& t : tris) {
      const uint32_t ab = midpoint(t.x, t.y), bc = midpoint(t.y, t.z), ca = midpoint(t.z, t.x);
      next.push_back({t.x, ab, ca});
      next.push_back({t.y, bc, ab});
      next.push_back({t.z, ca, bc});
      next.push_back({ab, bc, ca});
    }
    tris = std::move(next);
  }
  TriangleMesh mesh;
  mesh.positions.reserve(pos.size());
  for (const Vec3& dir : pos) mesh.positions.push_back(dir * rockRadius(dir, seed));
  mesh.triangles = std::move(tris);
  computeVertexNormals(mesh);
  return mesh;
}

TriangleMesh makeGridPlane(const Vec3& corner, const Vec3& edgeU, const Vec3& edgeV, int nu, int nv) {
  if (nu < 1 || nv < 1) throw Error("grid plane: nu and nv must be at least 1");
  TriangleMesh mesh;
  const Vec3 n = glm::normalize(glm::cross(edgeU, edgeV));
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      mesh.positions.push_back(corner + (float(i) / nu) * edgeU + (float(j) / nv) * edgeV);
      mesh.normals.push_back(n);
    }
  auto idx = [&](int i, int j) { return static_cast<uint32_t>(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      mesh.triangles.push_back({idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)});
      mesh.triangles.push_back({idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)});
    }
  return mesh;
}

}  // namespace penumbra
