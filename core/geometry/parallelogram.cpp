#include "core/geometry/parallelogram.h"

#include <array>
#include <cmath>
#include <optional>

namespace penumbra {
namespace {

// Corners closer than this (relative to the largest coordinate) count as the same parallelogram
// corner: ~8 float ulps, the rounding a transformed quad's vertices carry.
constexpr double kCornerTolerance = 0x1p-21;

double maxAbs(const DVec3& v) {
  return std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z)));
}

// The parallelogram c, a, e, b (diagonal a–b) if it is one: a + b = c + e within rounding,
// non-degenerate, with finite dual vectors. The triangle (c, a, b) keeps its winding.
std::optional<Parallelogram> makeParallelogram(const Vec3& c, const Vec3& a, const Vec3& e, const Vec3& b) {
  const DVec3 C(c), A(a), E(e), B(b);
  const double scale = std::max(std::max(maxAbs(C), maxAbs(A)), std::max(maxAbs(E), maxAbs(B)));
  if (!(maxAbs((A + B) - (C + E)) <= kCornerTolerance * scale)) return std::nullopt;
  const DVec3 e1 = A - C, e2 = B - C;
  DVec3 n = glm::cross(e1, e2);
  const double len = glm::length(n);
  if (!(len > 0.0) || !std::isfinite(len)) return std::nullopt;
  n /= len;
  // Dual vectors: du is orthogonal to e2 and n with du · e1 = 1 (dv likewise).
  const DVec3 perpE2 = glm::cross(e2, n), perpE1 = glm::cross(n, e1);
  const DVec3 du = perpE2 / glm::dot(e1, perpE2);
  const DVec3 dv = perpE1 / glm::dot(e2, perpE1);
  if (!std::isfinite(maxAbs(du)) || !std::isfinite(maxAbs(dv))) return std::nullopt;
  Parallelogram q{};
  q.p0 = c;
  q.n = Vec3(n);
  q.planeOffset = static_cast<float>(glm::dot(n, (C + A + E + B) * 0.25));
  q.du = Vec3(du);
  q.dv = Vec3(dv);
  q.ns = q.n;
  return q;
}

bool sameEdge(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (a == c && b == d) || (a == d && b == c);
}

}  // namespace

void fillParallelogramHit(const Parallelogram& q, const Ray& ray, float t, float u, float v,
                          uint32_t objectId, SurfaceHit& hit) {
  const DVec3 n(q.n);
  DVec3 p = DVec3(ray.o) + static_cast<double>(t) * DVec3(ray.d);
  p -= n * (glm::dot(n, p) - static_cast<double>(q.planeOffset));
  hit.t = t;
  hit.p = Vec3(p);
  hit.ng = q.n;
  hit.ns = q.ns;
  // The intersection test rejects origins within its rounding of the plane, so an offset relative to
  // |p| cannot re-hit it (as for brute-force triangles, see projectOntoPlane).
  hit.offsetScale = maxAbsComponent(hit.p);
  hit.objectId = objectId;
  hit.primId = u + v <= 1.f ? q.primLow : q.primHigh;
}

void pairParallelograms(const TriangleMesh& mesh, uint32_t meshIndex, std::vector<Parallelogram>& quads,
                        std::vector<uint32_t>& leftover) {
  const size_t count = mesh.triangles.size();
  auto corner = [&](size_t tri, int k) { return mesh.positions[mesh.triangles[tri][k % 3]]; };
  auto normalOf = [&](size_t tri, int k) { return mesh.normals[mesh.triangles[tri][k % 3]]; };
  // Whether any triangle other than i and j has the edge (a, b).
  auto sharedElsewhere = [&](size_t i, size_t j, const Vec3& a, const Vec3& b) {
    for (size_t o = 0; o < count; ++o) {
      if (o == i || o == j) continue;
      for (int k = 0; k < 3; ++k)
        if (sameEdge(a, b, corner(o, k), corner(o, k + 1))) return true;
    }
    return false;
  };

  std::vector<bool> used(count, false);
  for (size_t i = 0; i < count; ++i) {
    for (size_t j = i + 1; j < count && !used[i]; ++j) {
      if (used[j]) continue;
      // Edge a -> b of triangle i must appear as b -> a in triangle j (consistent winding).
      for (int k = 0; k < 3 && !used[i]; ++k) {
        const Vec3 a = corner(i, k), b = corner(i, k + 1), c = corner(i, k + 2);
        for (int m = 0; m < 3; ++m) {
          if (!(corner(j, m) == b && corner(j, m + 1) == a)) continue;
          const Vec3 e = corner(j, m + 2);
          std::optional<Parallelogram> q = makeParallelogram(c, a, e, b);
          if (!q) break;
          if (!mesh.normals.empty()) {
            const Vec3 n0 = normalOf(i, 0);
            bool uniform = true;
            for (int v = 0; v < 3; ++v) uniform = uniform && normalOf(i, v) == n0 && normalOf(j, v) == n0;
            if (!uniform) break;
            const float l = glm::length(n0);
            if (l > 0.f && std::isfinite(l)) q->ns = n0 / l;
          }
          if (sharedElsewhere(i, j, a, b) || sharedElsewhere(i, j, c, a) || sharedElsewhere(i, j, a, e) ||
              sharedElsewhere(i, j, e, b) || sharedElsewhere(i, j, b, c))
            break;
          q->mesh = meshIndex;
          q->primLow = static_cast<uint32_t>(i);
          q->primHigh = static_cast<uint32_t>(j);
          quads.push_back(*q);
          used[i] = used[j] = true;
          break;
        }
      }
    }
  }
  for (size_t i = 0; i < count; ++i)
    if (!used[i]) leftover.push_back(static_cast<uint32_t>(i));
}

}  // namespace penumbra
