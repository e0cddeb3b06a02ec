#include "core/lights/light_bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <utility>

namespace penumbra {
namespace {

// Importance is bounded so that a sum of two never overflows (a zero-radius light at p).
constexpr double kMaxImportance = 1e300;

struct BuildItem {
  Bounds box;
  Vec3 centroid;
  double power;
  uint32_t light;
  Vec3 coneAxis;
  float cosConeAngle;
};

double surfaceArea(const Bounds& b) {
  if (b.empty()) return 0.0;
  const DVec3 e = DVec3(b.max) - DVec3(b.min);
  return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

struct Builder {
  std::vector<BuildItem> items;
  LightBvh bvh;

  uint32_t build(uint32_t begin, uint32_t end, uint32_t parent) {
    const uint32_t index = static_cast<uint32_t>(bvh.nodes.size());
    bvh.nodes.emplace_back();
    Bounds box, centroids;
    double power = 0.0;
    Vec3 axis = items[begin].coneAxis;
    float cosAngle = items[begin].cosConeAngle;
    for (uint32_t i = begin; i < end; ++i) {
      box.expand(items[i].box);
      centroids.expand(items[i].centroid);
      power += items[i].power;
      if (i > begin) joinCones(axis, cosAngle, items[i].coneAxis, items[i].cosConeAngle);
    }
    {
      LightBvhNode& node = bvh.nodes[index];
      node.lo = box.min;
      node.hi = box.max;
      node.power = power;
      node.parent = parent;
      node.coneAxis = axis;
      node.cosConeAngle = cosAngle;
    }
    if (end - begin == 1) {
      bvh.nodes[index].leaf = true;
      bvh.nodes[index].child = items[begin].light;
      bvh.leafOf[items[begin].light] = index;
      return index;
    }
    const uint32_t mid = split(begin, end, centroids);
    build(begin, mid, index);
    const uint32_t second = build(mid, end, index);
    bvh.nodes[index].child = second;
    return index;
  }

  // The bucket of `it`'s centroid along `axis`, of `buckets` across the centroids' bounds. The ratio is
  // tested before the cast, which is defined only in range: centroids spanning an infinite extent give
  // NaN or infinite ratios, which go to the end buckets.
  static int bucket(const BuildItem& it, int axis, const Bounds& centroids, int buckets) {
    const float t = float(buckets) * ((it.centroid[axis] - centroids.min[axis]) / centroids.extent()[axis]);
    if (!(t >= 1.f)) return 0;
    return t < float(buckets) ? int(t) : buckets - 1;
  }

  // Bucketed split minimising power × surface area on each side, each axis weighted by how much
  // narrower than the widest it is (pbrt-v4's Kr); the median by centroid when no split separates.
  uint32_t split(uint32_t begin, uint32_t end, const Bounds& centroids) {
    constexpr int kBuckets = 12;
    const Vec3 extent = centroids.extent();
    const float maxExtent = maxComponent(extent);
    double bestCost = INFINITY;
    int bestAxis = -1, bestBucket = 0;
    for (int axis = 0; axis < 3 && maxExtent > 0.f; ++axis) {
      if (!(extent[axis] > 0.f)) continue;
      std::array<Bounds, kBuckets> boxes;
      std::array<double, kBuckets> powers{};
      auto bucketOf = [&](const BuildItem& it) { return bucket(it, axis, centroids, kBuckets); };
      for (uint32_t i = begin; i < end; ++i) {
        const int b = bucketOf(items[i]);
        boxes[b].expand(items[i].box);
        powers[b] += items[i].power;
      }
      const double kr = double(maxExtent) / double(extent[axis]);
      for (int s = 0; s < kBuckets - 1; ++s) {
        Bounds left, right;
        double pl = 0.0, pr = 0.0;
        int nl = 0, nr = 0;
        for (int b = 0; b <= s; ++b) left.expand(boxes[b]), pl += powers[b], nl += !boxes[b].empty();
        for (int b = s + 1; b < kBuckets; ++b)
          right.expand(boxes[b]), pr += powers[b], nr += !boxes[b].empty();
        if (nl == 0 || nr == 0) continue;
        // +1e-300 per side keeps zero-power subtrees ordered by area instead of all costing 0.
        const double cost = kr * ((pl + 1e-300) * surfaceArea(left) + (pr + 1e-300) * surfaceArea(right));
        if (cost < bestCost) {
          bestCost = cost;
          bestAxis = axis;
          bestBucket = s;
        }
      }
    }
    BuildItem* first = items.data() + begin;
    BuildItem* last = items.data() + end;
    if (bestAxis >= 0) {
      const int axis = bestAxis;
      BuildItem* midPtr = std::partition(first, last, [&](const BuildItem& it) {
        return bucket(it, axis, centroids, kBuckets) <= bestBucket;
      });
      if (midPtr != first && midPtr != last) return static_cast<uint32_t>(midPtr - items.data());
    }
    // Coincident centroids (or a failed partition): halves by count along the widest axis.
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (extent[a] > extent[axis]) axis = a;
    BuildItem* midPtr = first + (last - first) / 2;
    std::nth_element(first, midPtr, last, [axis](const BuildItem& a, const BuildItem& b) {
      return a.centroid[axis] < b.centroid[axis];
    });
    return static_cast<uint32_t>(midPtr - items.data());
  }
};

}  // namespace

// After pbrt-v4's LightBounds::Importance: power over the squared distance to the bounds' centre (at
// least the bounding sphere's radius squared), times the cosine bound cos(max(0, θi − θb)) of the
// receiver's normal over the cone θb that the bounding sphere subtends, times, for a node of one-sided
// emitters (normal cone θo < π), the bound cos(max(0, θw − θo − θb)) of the emitters' cosine towards p,
// θw the angle between the cone's axis and the direction from the centre to p: 0 past π/2, where no
// emitter of the node faces p.
double lightBvhImportance(const LightBvhNode& node, const Vec3& p, const Vec3& n) {
  if (!(node.power > 0.0)) return 0.0;
  const DVec3 lo(node.lo), hi(node.hi);
  const DVec3 c = 0.5 * (lo + hi);
  const double r2 = 0.25 * glm::dot(hi - lo, hi - lo);  // bounding sphere radius squared
  const DVec3 toCentre = c - DVec3(p);
  const double d2 = glm::dot(toCentre, toCentre);
  if (d2 <= r2) return std::min(node.power / std::max(r2, 1e-300), kMaxImportance);  // p inside
  const double sin2b = r2 / d2;
  const double cosb = std::sqrt(1.0 - sin2b), sinb = std::sqrt(sin2b);
  double cosBound = 1.0;
  const DVec3 nd(n);
  if (nd != DVec3(0.0)) {
    const double cosi = glm::dot(nd, toCentre) / std::sqrt(d2);
    if (cosi < cosb) {
      const double sini = std::sqrt(std::max(0.0, 1.0 - cosi * cosi));
      cosBound = cosi * cosb + sini * sinb;  // cos(θi − θb)
      if (!(cosBound > 0.0)) return 0.0;     // the whole bounding sphere is below the horizon
    }
  }
  if (node.cosConeAngle > -1.f) {
    // θw − θo − θb as one angle: cos and sin of θw − θo first, then less θb.
    const double cosw = -glm::dot(DVec3(node.coneAxis), toCentre) / std::sqrt(d2);
    const double sinw = std::sqrt(std::max(0.0, 1.0 - cosw * cosw));
    const double coso = double(node.cosConeAngle), sino = std::sqrt(std::max(0.0, 1.0 - coso * coso));
    if (cosw < coso) {  // θw > θo
      const double cosx = cosw * coso + sinw * sino, sinx = sinw * coso - cosw * sino;
      if (cosx < cosb) {  // θw − θo > θb
        const double cosEmit = cosx * cosb + sinx * sinb;
        if (!(cosEmit > 0.0)) return 0.0;  // no emitter of the node faces p
        cosBound *= cosEmit;
      }
    }
  }
  return std::min(node.power * cosBound / d2, kMaxImportance);
}

void joinCones(Vec3& axis, float& cosAngle, const Vec3& otherAxis, float otherCosAngle) {
  if (cosAngle <= -1.f) return;
  if (otherCosAngle <= -1.f) {
    axis = otherAxis;
    cosAngle = -1.f;
    return;
  }
  const DVec3 a(axis), b(otherAxis);
  const double thetaA = std::acos(std::clamp(double(cosAngle), -1.0, 1.0));
  const double thetaB = std::acos(std::clamp(double(otherCosAngle), -1.0, 1.0));
  const double thetaD = std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
  constexpr double kPiD = 3.14159265358979323846;
  if (std::min(thetaD + thetaB, kPiD) <= thetaA) return;  // the first holds the second
  if (std::min(thetaD + thetaA, kPiD) <= thetaB) {
    axis = otherAxis;
    cosAngle = otherCosAngle;
    return;
  }
  const double thetaO = 0.5 * (thetaA + thetaD + thetaB);
  const DVec3 across = glm::cross(a, b);
  const double acrossLength = glm::length(across);
  if (thetaO >= kPiD || !(acrossLength > 1e-12)) {
    cosAngle = -1.f;
    return;
  }
  // The axis turned from a towards b by θo − θa, in the plane of the two.
  const double turn = thetaO - thetaA;
  const DVec3 towardsB = glm::cross(across / acrossLength, a);
  axis = Vec3(glm::normalize(std::cos(turn) * a + std::sin(turn) * towardsB));
  // Rounded outwards by a little, so the joined cone keeps holding both after float rounding.
  cosAngle = float(std::cos(std::min(kPiD, thetaO + 1e-6)));
}

namespace {

// The probabilities of taking the first and the second child of an interior node. When neither
// child's bounds can reach p although the node's can (their bounding spheres are tighter), the
// split falls back to power alone: those lights add nothing at p, but the probabilities of all
// lights still sum to 1.
inline std::pair<double, double> childProbabilities(const LightBvh& bvh, uint32_t node, const Vec3& p,
                                                    const Vec3& n) {
  const LightBvhNode& a = bvh.nodes[node + 1];
  const LightBvhNode& b = bvh.nodes[bvh.nodes[node].child];
  double ia = lightBvhImportance(a, p, n), ib = lightBvhImportance(b, p, n);
  if (!(ia + ib > 0.0)) {
    ia = a.power;
    ib = b.power;
  }
  const double sum = ia + ib;
  if (!(sum > 0.0)) return {0.0, 0.0};  // a subtree of dark lights: never entered
  return {ia / sum, ib / sum};
}

}  // namespace

LightPick LightBvh::pick(const Vec3& p, const Vec3& n, double u) const {
  // Nothing at all when the root's bounds cannot reach p (then no light can).
  if (nodes.empty() || !(lightBvhImportance(nodes[0], p, n) > 0.0)) return {};
  uint32_t index = 0;
  double pmf = 1.0;
  while (!nodes[index].leaf) {
    const auto [pa, pb] = childProbabilities(*this, index, p, n);
    if (u < pa) {
      index = index + 1;
      pmf *= pa;
      u = u / pa;
    } else {
      if (!(pb > 0.0)) return {};
      index = nodes[index].child;
      pmf *= pb;
      u = (u - pa) / pb;
    }
    u = std::min(u, 0x1.fffffffffffffp-1);  // keep u in [0, 1) after rounding
  }
  return {nodes[index].child, pmf};
}

double LightBvh::pmf(const Vec3& p, const Vec3& n, uint32_t light) const {
  if (!(lightBvhImportance(nodes[0], p, n) > 0.0)) return 0.0;
  double pmf = 1.0;
  for (uint32_t index = leafOf[light]; index != 0;) {
    const uint32_t parent = nodes[index].parent;
    const auto [pa, pb] = childProbabilities(*this, parent, p, n);
    pmf *= index == parent + 1 ? pa : pb;
    index = parent;
  }
  return pmf;
}

LightBvh makeLightBvh(std::span<const LightSummary> lights) {
  Builder builder;
  builder.bvh.leafOf.resize(lights.size());
  if (lights.empty()) return builder.bvh;
  double total = 0.0;
  for (const LightSummary& l : lights) total += l.power;
  const bool unitPower = !(total > 0.0);  // every light dark: choose by geometry alone
  for (uint32_t i = 0; i < lights.size(); ++i) {
    const LightSummary& l = lights[i];
    builder.items.push_back({l.box, l.centroid, unitPower ? 1.0 : l.power, i, l.coneAxis, l.cosConeAngle});
  }
  builder.bvh.nodes.reserve(2 * lights.size());
  builder.build(0, static_cast<uint32_t>(lights.size()), 0);
  return builder.bvh;
}

}  // namespace penumbra
