#include "core/lights/projected_polygon.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/math/frame.h"

namespace penumbra {

namespace {

struct Azimuth {
  double x, y;  // unit vector in the local xy plane
};

// a turned counter-clockwise by t; sinT = sin t.
Azimuth rotated(const Azimuth& a, double t, double& sinT) {
  const double c = std::cos(t), s = std::sin(t);
  sinT = s;
  return {a.x * c - a.y * s, a.x * s + a.y * c};
}

// Counter-clockwise angle from a to b, in (−π, π].
double angleBetween(const Azimuth& a, const Azimuth& b) {
  return std::atan2(a.x * b.y - a.y * b.x, a.x * b.x + a.y * b.y);
}

// The boundary edge on the great circle with unit normal m (see ProjectedPolygon::Edge).
ProjectedPolygon::Edge edgeOf(const DVec3& m) {
  ProjectedPolygon::Edge e;
  e.k = std::fabs(m.z);
  e.c2 = m.x * m.x + m.y * m.y;
  const double len = std::sqrt(e.c2);
  if (len > 0) {
    const double sign = m.z < 0 ? 1.0 : -1.0;  // the upper half circle is where cos ψ ≥ 0
    e.qx = sign * m.x / len;
    e.qy = sign * m.y / len;
  } else {
    e.qx = 1, e.qy = 0;  // the horizon: every azimuth is alike
  }
  return e;
}

double cosPsi(const ProjectedPolygon::Edge& e, const Azimuth& u) {
  return std::max(0.0, e.qx * u.x + e.qy * u.y);
}
double sinPsi(const ProjectedPolygon::Edge& e, const Azimuth& u) {
  return e.qx * u.y - e.qy * u.x;
}

// r² and z² = 1 − r² of the edge's point at azimuth u, each without cancellation.
void radiusAt(const ProjectedPolygon::Edge& e, const Azimuth& u, double& r2, double& z2) {
  const double cc = e.c2 * cosPsi(e, u) * cosPsi(e, u), k2 = e.k * e.k;
  const double sum = k2 + cc;
  if (!(sum > 0)) {  // an edge through the normal's direction, seen along it
    r2 = 0, z2 = 1;
    return;
  }
  r2 = k2 / sum;
  z2 = cc / sum;
}

// Area swept by the edge's ellipse from azimuth u0 to u1, t radians further (sin t given): one atan2
// of the difference of the two arctangents, ½ k (atan(k tan ψ₁) − atan(k tan ψ₀)).
double sweptArea(const ProjectedPolygon::Edge& e, const Azimuth& u0, const Azimuth& u1, double sinT,
                 double t) {
  if (e.c2 == 0) return 0.5 * t;  // the horizon, r = 1 (its ψ is arbitrary: no upper half to clamp to)
  const double c0 = cosPsi(e, u0), s0 = sinPsi(e, u0), c1 = cosPsi(e, u1), s1 = sinPsi(e, u1);
  return 0.5 * e.k * std::atan2(e.k * sinT, c0 * c1 + e.k * e.k * s0 * s1);
}

}  // namespace

double ProjectedPolygon::wedgeAreaTo(const Wedge& w, double ux, double uy, double sinT, double t) {
  const Azimuth u0{w.ux, w.uy}, u1{ux, uy};
  double area = sweptArea(w.outer, u0, u1, sinT, t);
  if (w.hasInner) area -= sweptArea(w.inner, u0, u1, sinT, t);
  return std::max(0.0, area);
}

bool ProjectedPolygon::init(const Vec3* vertices, int count, const Vec3& x, const Vec3& n) {
  projectedSolidAngle = 0;
  wedgeCount = 0;
  edgeCount = 0;
  if (count < 3 || count > kMaxInputVertices) return false;
  ez = glm::normalize(DVec3(n));
  orthonormalBasis(ez, ex, ey);
  auto toLocal = [&](const DVec3& v) { return DVec3(glm::dot(v, ex), glm::dot(v, ey), glm::dot(v, ez)); };

  // Wound so that the inside is where m · w ≥ 0 for every edge normal m: (v0 − x) · ((v1 − v0) × (v2 − v1))
  // > 0. In the polygon's plane: nothing to sample.
  auto rel = [&](int i) { return toLocal(DVec3(vertices[i]) - DVec3(x)); };
  auto edge = [&](int i, int j) { return toLocal(DVec3(vertices[j]) - DVec3(vertices[i])); };
  const DVec3 planeNormal = glm::cross(edge(0, 1), edge(1, 2));
  const double side = glm::dot(rel(0), planeNormal);
  if (!(std::fabs(side) > 1e-12 * glm::length(rel(0)) * glm::length(planeNormal))) return false;
  int order[kMaxInputVertices];
  for (int i = 0; i < count; ++i) order[i] = side > 0 ? i : (count - i) % count;  // reversed: 0, n-1, ..., 1
  // Vertices relative to x and edge normals (v_i − x) × (v_i+1 − v_i), formed from the edge vector: no
  // cancellation for a small polygon far away.
  DVec3 pts[kMaxInputVertices], m[kMaxInputVertices];
  for (int i = 0; i < count; ++i) {
    pts[i] = rel(order[i]);
    m[i] = glm::cross(pts[i], edge(order[i], order[(i + 1) % count]));
  }

  // Clip to the upper half space (Sutherland–Hodgman); each output vertex carries the normal of the edge
  // that starts at it: the original edge's (its part above the horizon lies on the same great circle)
  // or, from a point where the polygon leaves the upper half space, the horizon's.
  DVec3 clipped[kMaxVertices], normals[kMaxVertices];
  int vertexCount = 0;
  for (int i = 0; i < count; ++i) {
    const DVec3& a = pts[i];
    const DVec3& b = pts[(i + 1) % count];
    const bool aIn = a.z >= 0, bIn = b.z >= 0;
    if (aIn) clipped[vertexCount] = a, normals[vertexCount++] = m[i];
    if (aIn != bIn) {
      DVec3 p = a + (b - a) * (a.z / (a.z - b.z));
      p.z = 0;
      clipped[vertexCount] = p;
      normals[vertexCount++] = aIn ? DVec3(0, 0, 1) : m[i];
    }
  }
  if (vertexCount < 3) return false;

  // Unit edge normals; the zenith is inside when every edge has it on its inner side.
  bool zenithInside = true;
  for (int i = 0; i < vertexCount; ++i) {
    const double len = glm::length(normals[i]);
    edgeNormals[i] = len > 0 ? normals[i] / len : DVec3(0);
    if (edgeNormals[i].z < 0) zenithInside = false;
  }
  edgeCount = vertexCount;

  // Each vertex's azimuth (a vertex at the zenith has none: its edges are radial and sweep nothing).
  Azimuth az[kMaxVertices];
  bool hasAzimuth[kMaxVertices];
  for (int i = 0; i < vertexCount; ++i) {
    const double len = std::hypot(clipped[i].x, clipped[i].y);
    hasAzimuth[i] = len > 0;
    az[i] = hasAzimuth[i] ? Azimuth{clipped[i].x / len, clipped[i].y / len} : Azimuth{1, 0};
  }

  // A wedge from azimuth `from` to `to`, `span` radians (below π) apart, halved at their bisector when
  // it spans more than π/2; its area from the two vectors (sin span = from × to: no rotation).
  auto addWedge = [&](const Azimuth& from, const Azimuth& to, double span, const Edge& outer,
                      const Edge* inner) {
    if (!(span > 0)) return;
    Azimuth ends[3] = {from, to, to};
    int pieces = 1;
    if (span > 0.5 * kPiD) {
      const double bx = from.x + to.x, by = from.y + to.y, len = std::hypot(bx, by);
      ends[1] = Azimuth{bx / len, by / len};
      pieces = 2;
    }
    for (int p = 0; p < pieces; ++p) {
      Wedge& w = wedges[wedgeCount++];
      const Azimuth &a = ends[p], &b = ends[p + 1];
      w.ux = a.x, w.uy = a.y, w.span = span / pieces;
      w.outer = outer;
      w.hasInner = inner != nullptr;
      if (inner) w.inner = *inner;
      w.area = wedgeAreaTo(w, b.x, b.y, a.x * b.y - a.y * b.x, w.span);
    }
  };

  if (zenithInside) {
    // The region is star-shaped about the origin: one wedge per edge, from 0 to the edge.
    for (int i = 0; i < vertexCount; ++i) {
      const int j = (i + 1) % vertexCount;
      if (!hasAzimuth[i] || !hasAzimuth[j]) continue;
      addWedge(az[i], az[j], std::max(0.0, angleBetween(az[i], az[j])), edgeOf(edgeNormals[i]), nullptr);
    }
  } else {
    // The region spans less than π in azimuth: between consecutive vertex azimuths it lies between one
    // edge of each chain from the first vertex (in azimuth) to the last.
    double sx = 0, sy = 0;
    for (int i = 0; i < vertexCount; ++i) sx += az[i].x, sy += az[i].y;
    const double len = std::hypot(sx, sy);
    if (!(len > 0)) return false;
    const Azimuth ref{sx / len, sy / len};
    double alpha[kMaxVertices];
    int lo = 0, hi = 0;
    for (int i = 0; i < vertexCount; ++i) {
      alpha[i] = angleBetween(ref, az[i]);
      if (alpha[i] < alpha[lo]) lo = i;
      if (alpha[i] > alpha[hi]) hi = i;
    }
    // The two chains from lo to hi, as lists of edges (edge i runs from vertex i to i + 1).
    int chainA[kMaxVertices], chainB[kMaxVertices], lenA = 0, lenB = 0;
    for (int i = lo; i != hi; i = (i + 1) % vertexCount) chainA[lenA++] = i;
    for (int i = lo; i != hi; i = (i + vertexCount - 1) % vertexCount)
      chainB[lenB++] = (i + vertexCount - 1) % vertexCount;
    int order[kMaxVertices];
    for (int i = 0; i < vertexCount; ++i) order[i] = i;
    std::sort(order, order + vertexCount, [&](int p, int q) { return alpha[p] < alpha[q]; });
    // The chain edge whose azimuth range holds `mid` (chains run monotonically in azimuth).
    auto edgeAt = [&](const int* chain, int length, bool forward, double mid) {
      for (int c = 0; c < length; ++c) {
        const int i = chain[c];
        const int a = i, b = (i + 1) % vertexCount;
        const double end = forward ? alpha[b] : alpha[a];
        if (end >= mid || c == length - 1) return i;
      }
      return chain[length - 1];
    };
    for (int s = 0; s + 1 < vertexCount; ++s) {
      const Azimuth &from = az[order[s]], &to = az[order[s + 1]];
      const double span = alpha[order[s + 1]] - alpha[order[s]];
      if (!(span > 0)) continue;
      const double mid = 0.5 * (alpha[order[s]] + alpha[order[s + 1]]);
      const Edge ea = edgeOf(edgeNormals[edgeAt(chainA, lenA, true, mid)]);
      const Edge eb = edgeOf(edgeNormals[edgeAt(chainB, lenB, false, mid)]);
      const double bx = from.x + to.x, by = from.y + to.y, len = std::hypot(bx, by);  // the bisector
      const Azimuth um{bx / len, by / len};
      double ra, rb, za, zb;
      radiusAt(ea, um, ra, za);
      radiusAt(eb, um, rb, zb);
      if (ra >= rb)
        addWedge(from, to, span, ea, &eb);
      else
        addWedge(from, to, span, eb, &ea);
    }
  }

  cumulativeArea[0] = 0;
  for (int i = 0; i < wedgeCount; ++i) cumulativeArea[i + 1] = cumulativeArea[i] + wedges[i].area;
  projectedSolidAngle = cumulativeArea[wedgeCount];
  if (!(projectedSolidAngle > 0) || !std::isfinite(projectedSolidAngle)) {
    projectedSolidAngle = 0;
    wedgeCount = 0;
    return false;
  }
  return true;
}

DVec3 ProjectedPolygon::sampleDirection(Vec2 u) const {
  const double target = double(u.x) * projectedSolidAngle;
  int i = 0;
  while (i + 1 < wedgeCount && cumulativeArea[i + 1] <= target) ++i;
  const Wedge& w = wedges[i];
  const double tau = std::clamp(target - cumulativeArea[i], 0.0, w.area);

  // Newton's method on the wedge's area below azimuth t, safeguarded by bisection.
  double lo = 0, hi = w.span;
  double t = w.area > 0 ? w.span * (tau / w.area) : 0;
  const double tolerance = kAreaTolerance * w.area;
  const double ulps = 4 * std::numeric_limits<double>::epsilon() * w.span;
  const Azimuth u0{w.ux, w.uy};
  double sinT;
  Azimuth ut = rotated(u0, t, sinT);  // kept for the final t
  for (int step = 0; step < kMaxInversionSteps && hi - lo > ulps; ++step) {
    const double f = wedgeAreaTo(w, ut.x, ut.y, sinT, t) - tau;
    if (std::fabs(f) <= tolerance) break;
    (f < 0 ? lo : hi) = t;
    double rOuter2, zOuter2, rInner2 = 0, zInner2 = 1;
    radiusAt(w.outer, ut, rOuter2, zOuter2);
    if (w.hasInner) radiusAt(w.inner, ut, rInner2, zInner2);
    const double slope = 0.5 * (rOuter2 - rInner2);
    const double next = slope > 0 ? t - f / slope : lo - 1;
    t = next > lo && next < hi ? next : 0.5 * (lo + hi);
    ut = rotated(u0, t, sinT);
  }

  // r² uniform between the wedge's edges at azimuth t; z² the same way, each without cancellation.
  double rOuter2, zOuter2, rInner2 = 0, zInner2 = 1;
  radiusAt(w.outer, ut, rOuter2, zOuter2);
  if (w.hasInner) radiusAt(w.inner, ut, rInner2, zInner2);
  const double v = u.y;
  const double r = std::sqrt(std::max(0.0, (1 - v) * rInner2 + v * rOuter2));
  const double z = std::sqrt(std::max(0.0, (1 - v) * zInner2 + v * zOuter2));
  return glm::normalize(ex * (r * ut.x) + ey * (r * ut.y) + ez * z);
}

double ProjectedPolygon::pdfDirection(const DVec3& w) const {
  if (!(projectedSolidAngle > 0)) return 0;
  const DVec3 local(glm::dot(w, ex), glm::dot(w, ey), glm::dot(w, ez));
  if (!(local.z > 0)) return 0;
  // A direction the map produced lies inside to rounding: allow 1e-12 (radians) outside each edge.
  for (int i = 0; i < edgeCount; ++i)
    if (glm::dot(edgeNormals[i], local) < -1e-12) return 0;
  return local.z / projectedSolidAngle;
}

}  // namespace penumbra
