#include "core/lights/projected_polygon.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/math/frame.h"
#include "core/math/portable_atan2.h"

namespace penumbra {

namespace {

using Edge = ProjectedPolygon::Edge;
using Wedge = ProjectedPolygon::Wedge;

struct Azimuth {
  double x, y;  // a vector in the local xy plane
};

double cross(const Azimuth& a, const Azimuth& b) {
  return a.x * b.y - a.y * b.x;
}
double dot(const Azimuth& a, const Azimuth& b) {
  return a.x * b.x + a.y * b.y;
}

// A number that grows with the counter-clockwise angle from ref to a over (−π, π] (no atan2: only the
// order of the vertices' azimuths is needed).
double pseudoAngle(const Azimuth& ref, const Azimuth& a) {
  const double x = dot(ref, a), y = cross(ref, a);
  const double q = y / (std::fabs(x) + std::fabs(y));
  return x >= 0 ? q : (y >= 0 ? 2 - q : -2 - q);
}

// The boundary edge on the great circle with unit normal m (see ProjectedPolygon::Edge), without its
// wedge's terms.
Edge edgeOf(const DVec3& m) {
  Edge e{};
  e.k = std::fabs(m.z);
  const double sign = m.z < 0 ? 1.0 : -1.0;  // the upper half circle is where g · v ≥ 0
  e.gx = sign * m.x;
  e.gy = sign * m.y;
  return e;
}

double gDot(const Edge& e, const Azimuth& v) {
  return e.gx * v.x + e.gy * v.y;
}

// atan(y / x) for x > 0: the series when the ratio is small (an iterate's step), else atan2.
double atanStep(double y, double x) {
  if (std::fabs(y) <= 0x1p-6 * x) {
    const double z = y / x, z2 = z * z;  // truncated after z⁹: below 2^-60 of the value
    return z * (1 + z2 * (-1.0 / 3 + z2 * (1.0 / 5 + z2 * (-1.0 / 7 + z2 * (1.0 / 9)))));
  }
  return portableAtan2(y, x);
}

// The edge's terms in a wedge from a to a + d (σ = a × d): its start, its swept area at λ = 1 and the
// model αλ / (1 + βλ) of its area (slope α at 0, that area at 1).
double placeEdge(Edge& e, const Azimuth& a, const Azimuth& d, double sigma) {
  const double ga = gDot(e, a);
  e.p0 = e.k * e.k + ga * ga;
  e.pd = e.k * e.k * dot(a, d) + ga * gDot(e, d);
  const double area = 0.5 * e.k * portableAtan2(e.k * sigma, e.p0 + e.pd);
  e.alpha = e.p0 > 0 ? 0.5 * e.k * e.k * sigma / e.p0 : 0;
  e.beta = area > 0 ? e.alpha / area - 1 : 0;
  return area;
}

// m_z² / |P(v)|² (= r² / |v|²) and (g · v)² / |P(v)|² (= z²) of the edge's point at azimuth v.
void radiusAt(const Edge& e, double gv, double v2, double& rho2, double& z2) {
  const double k2 = e.k * e.k, sum = k2 * v2 + gv * gv;
  if (!(sum > 0)) {  // an edge through the normal's direction, seen along it
    rho2 = 0, z2 = 1;
    return;
  }
  rho2 = k2 / sum;
  z2 = gv * gv / sum;
}

}  // namespace

int ProjectedPolygon::azimuthIntervals(const double* alpha, int vertexCount, AzimuthInterval* out) {
  int lo = 0, hi = 0;
  for (int i = 0; i < vertexCount; ++i) {
    if (alpha[i] < alpha[lo]) lo = i;
    if (alpha[i] > alpha[hi]) hi = i;
  }
  // The two chains from lo to hi, as lists of edges (edge i runs from vertex i to i + 1).
  int chainA[kMaxVertices], chainB[kMaxVertices], lenA = 0, lenB = 0;
  for (int i = lo; i != hi; i = (i + 1) % vertexCount) chainA[lenA++] = i;
  for (int i = lo; i != hi; i = (i + vertexCount - 1) % vertexCount)
    chainB[lenB++] = (i + vertexCount - 1) % vertexCount;
  // The vertices in azimuth order (insertion sort: at most five).
  int order[kMaxVertices];
  for (int i = 0; i < vertexCount; ++i) {
    int j = i;
    for (; j > 0 && alpha[order[j - 1]] > alpha[i]; --j) order[j] = order[j - 1];
    order[j] = i;
  }
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
  int count = 0;
  for (int s = 0; s + 1 < vertexCount; ++s) {
    if (!(alpha[order[s + 1]] > alpha[order[s]])) continue;
    const double mid = 0.5 * (alpha[order[s]] + alpha[order[s + 1]]);
    out[count++] = {order[s], order[s + 1], edgeAt(chainA, lenA, true, mid),
                    edgeAt(chainB, lenB, false, mid)};
  }
  return count;
}

int ProjectedPolygon::clipToUpperHalfSpace(const DVec3* points, const DVec3* normals, int count,
                                           DVec3* clipped, DVec3* clippedNormals) {
  int out = 0;
  for (int i = 0; i < count; ++i) {
    const DVec3& a = points[i];
    const DVec3& b = points[(i + 1) % count];
    const bool aIn = a.z >= 0, bIn = b.z >= 0;
    if (aIn) clipped[out] = a, clippedNormals[out++] = normals[i];
    if (aIn != bIn) {
      DVec3 p = a + (b - a) * (a.z / (a.z - b.z));
      p.z = 0;
      clipped[out] = p;
      clippedNormals[out++] = aIn ? DVec3(0, 0, 1) : normals[i];
    }
  }
  return out;
}

bool ProjectedPolygon::init(const Vec3* vertices, int count, const Vec3& x, const Vec3& n) {
  projectedSolidAngle = 0;
  wedgeCount = 0;
  edgeCount = 0;
  if (count < 3 || count > kMaxInputVertices) return false;
  ez = glm::normalize(DVec3(n));
  orthonormalBasis(ez, ex, ey);
  auto toLocal = [&](const DVec3& v) { return DVec3(glm::dot(v, ex), glm::dot(v, ey), glm::dot(v, ez)); };

  // Vertices relative to x and edge vectors, in the local frame.
  DVec3 rel[kMaxInputVertices], edges[kMaxInputVertices];
  for (int i = 0; i < count; ++i) {
    rel[i] = toLocal(DVec3(vertices[i]) - DVec3(x));
    edges[i] = toLocal(DVec3(vertices[(i + 1) % count]) - DVec3(vertices[i]));
  }
  // Wound so that the inside is where m · w ≥ 0 for every edge normal m: (v0 − x) · ((v1 − v0) × (v2 − v1))
  // > 0. In the polygon's plane: nothing to sample.
  const DVec3 planeNormal = glm::cross(edges[0], edges[1]);
  const double side = glm::dot(rel[0], planeNormal);
  if (!(side * side > 1e-24 * glm::dot(rel[0], rel[0]) * glm::dot(planeNormal, planeNormal))) return false;
  // Edge normals (v_i − x) × (v_i+1 − v_i), formed from the edge vector: no cancellation for a small
  // polygon far away. Reversed (0, n-1, ..., 1), edge i runs back along an original edge.
  DVec3 pts[kMaxInputVertices], m[kMaxInputVertices];
  for (int i = 0; i < count; ++i) {
    if (side > 0) {
      pts[i] = rel[i];
      m[i] = glm::cross(rel[i], edges[i]);
    } else {
      const int j = (count - i) % count, p = (j + count - 1) % count;
      pts[i] = rel[j];
      m[i] = glm::cross(rel[j], -edges[p]);
    }
  }

  DVec3 clipped[kMaxVertices], normals[kMaxVertices];
  const int vertexCount = clipToUpperHalfSpace(pts, m, count, clipped, normals);
  if (vertexCount < 3) return false;

  // Unit edge normals; the zenith is inside when every edge has it on its inner side.
  bool zenithInside = true;
  for (int i = 0; i < vertexCount; ++i) {
    const double len2 = glm::dot(normals[i], normals[i]);
    edgeNormals[i] = len2 > 0 ? normals[i] * (1 / std::sqrt(len2)) : DVec3(0);
    if (edgeNormals[i].z < 0) zenithInside = false;
  }
  edgeCount = vertexCount;

  // Each vertex's unit azimuth vector (a vertex at the zenith has none: its edges are radial and sweep
  // nothing).
  Azimuth az[kMaxVertices];
  bool hasAzimuth[kMaxVertices];
  for (int i = 0; i < vertexCount; ++i) {
    const double len2 = clipped[i].x * clipped[i].x + clipped[i].y * clipped[i].y;
    hasAzimuth[i] = len2 > 0;
    const double inv = hasAzimuth[i] ? 1 / std::sqrt(len2) : 0;
    az[i] = hasAzimuth[i] ? Azimuth{clipped[i].x * inv, clipped[i].y * inv} : Azimuth{1, 0};
  }

  // A wedge from azimuth a counter-clockwise to b, less than π apart.
  auto placeWedge = [&](const Azimuth& a, const Azimuth& b, const Edge& outer, const Edge* inner) {
    Wedge& w = wedges[wedgeCount++];
    const Azimuth d{b.x - a.x, b.y - a.y};
    w.ax = a.x, w.ay = a.y, w.dx = d.x, w.dy = d.y;
    w.sigma = cross(a, d);
    w.outer = outer;
    w.hasInner = inner != nullptr;
    w.area = placeEdge(w.outer, a, d, w.sigma);
    if (inner) {
      w.inner = *inner;
      w.area -= placeEdge(w.inner, a, d, w.sigma);
    }
    w.area = std::max(0.0, w.area);
  };
  // The same, halved at the bisector when it spans more than 3π/4: the chord then passes no nearer to
  // the origin than cos(3π/8) ≈ 0.38, so the azimuth along it keeps its precision.
  auto addWedge = [&](const Azimuth& from, const Azimuth& to, const Edge& outer, const Edge* inner) {
    if (!(cross(from, to) > 0)) return;
    if (dot(from, to) < -0.70710678118654752) {
      // The bisector as the sum of `from` and `to` each turned a quarter towards the other (less than
      // π/4 apart: no cancellation).
      const double bx = to.y - from.y, by = from.x - to.x, inv = 1 / std::hypot(bx, by);
      const Azimuth mid{bx * inv, by * inv};
      placeWedge(from, mid, outer, inner);
      placeWedge(mid, to, outer, inner);
    } else {
      placeWedge(from, to, outer, inner);
    }
  };

  if (zenithInside) {
    // The region is star-shaped about the origin: one wedge per edge, from 0 to the edge.
    for (int i = 0; i < vertexCount; ++i) {
      const int j = (i + 1) % vertexCount;
      if (!hasAzimuth[i] || !hasAzimuth[j]) continue;
      addWedge(az[i], az[j], edgeOf(edgeNormals[i]), nullptr);
    }
  } else {
    // The region spans less than π in azimuth: between consecutive vertex azimuths it lies between one
    // edge of each chain from the first vertex (in azimuth) to the last.
    Azimuth ref{0, 0};
    for (int i = 0; i < vertexCount; ++i) ref.x += az[i].x, ref.y += az[i].y;
    if (!(ref.x * ref.x + ref.y * ref.y > 0)) return false;
    double alpha[kMaxVertices];
    for (int i = 0; i < vertexCount; ++i) alpha[i] = pseudoAngle(ref, az[i]);
    AzimuthInterval intervals[kMaxVertices];
    const int intervalCount = azimuthIntervals(alpha, vertexCount, intervals);
    for (int s = 0; s < intervalCount; ++s) {
      const AzimuthInterval& interval = intervals[s];
      const Azimuth &from = az[interval.from], &to = az[interval.to];
      const Edge ea = edgeOf(edgeNormals[interval.edgeA]);
      const Edge eb = edgeOf(edgeNormals[interval.edgeB]);
      // The outer edge at an azimuth inside: r² = k² |v|² / (k² |v|² + (g · v)²) is the larger.
      const Azimuth um{from.x + to.x, from.y + to.y};
      if (ea.k * std::fabs(gDot(eb, um)) >= eb.k * std::fabs(gDot(ea, um)))
        addWedge(from, to, ea, &eb);
      else
        addWedge(from, to, eb, &ea);
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
  const Edge &eo = w.outer, &ei = w.inner;
  const double tau = std::clamp(target - cumulativeArea[i], 0.0, w.area);

  // The first λ: the model's root in [0, 1], where αo λ / (1 + βo λ) − αi λ / (1 + βi λ) = τ, i.e.
  // c2 λ² + c1 λ + τ = 0 (positive at 0, at most 0 at 1); else λ proportional to τ.
  double t = w.area > 0 ? tau / w.area : 0;
  {
    const double ao = eo.alpha, bo = eo.beta, ai = w.hasInner ? ei.alpha : 0, bi = w.hasInner ? ei.beta : 0;
    const double c2 = tau * bo * bi - ao * bi + ai * bo, c1 = tau * (bo + bi) - ao + ai;
    const double disc = c1 * c1 - 4 * c2 * tau;
    if (disc >= 0) {
      const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
      const double r1 = tau / q, r2 = q / c2;
      if (r1 >= 0 && r1 <= 1)
        t = r1;
      else if (r2 >= 0 && r2 <= 1)
        t = r2;
    }
  }
  // Against the horizon (a circle in the projection, not a line) the model is poor where the wedge's
  // width vanishes at an end (an edge meets the horizon tangentially there): two Newton steps on the
  // cubic with the wedge's area and its slopes at both ends.
  if (eo.gx == 0 && eo.gy == 0) {
    const Azimuth v1{w.ax + w.dx, w.ay + w.dy};
    const double q1 = dot(v1, v1), go1 = gDot(eo, v1);
    double s1 = eo.k * eo.k / (eo.k * eo.k * q1 + go1 * go1);
    if (w.hasInner) {
      const double gi1 = gDot(ei, v1);
      s1 -= ei.k * ei.k / (ei.k * ei.k * q1 + gi1 * gi1);
    }
    s1 *= 0.5 * w.sigma;
    const double s0 = eo.alpha - (w.hasInner ? ei.alpha : 0), a1 = w.area;
    if (s0 < 1e-2 * a1 || s1 < 1e-2 * a1) {
      const double h2 = 3 * a1 - 2 * s0 - s1, h3 = s0 + s1 - 2 * a1;
      for (int k = 0; k < 2; ++k) {
        const double h = t * (s0 + t * (h2 + t * h3)) - tau, dh = s0 + t * (2 * h2 + 3 * t * h3);
        const double next = dh > 0 ? t - h / dh : -1;
        if (next >= 0 && next <= 1) t = next;
      }
    }
  }

  // Newton's method on the wedge's area below v(λ), safeguarded by bisection. The area once in full, then
  // by the step between iterates: ½ k atan2((λ' − λ) k σ, P(v) · P(v')).
  double lo = 0, hi = 1;
  const double tolerance = kAreaTolerance * w.area;
  const double ulps = 4 * std::numeric_limits<double>::epsilon();
  const Azimuth a{w.ax, w.ay}, d{w.dx, w.dy};
  Azimuth v{a.x + t * d.x, a.y + t * d.y};
  double go = gDot(eo, v), gi = w.hasInner ? gDot(ei, v) : 0;
  double area = 0.5 * eo.k * portableAtan2(t * eo.k * w.sigma, eo.p0 + t * eo.pd);
  if (w.hasInner) area -= 0.5 * ei.k * portableAtan2(t * ei.k * w.sigma, ei.p0 + t * ei.pd);
  for (int step = 0; step < kMaxInversionSteps; ++step) {
    const double f = area - tau;
    if (std::fabs(f) <= tolerance) break;
    (f < 0 ? lo : hi) = t;
    if (!(hi - lo > ulps)) break;
    const double v2 = dot(v, v);
    double slope = eo.k * eo.k / (eo.k * eo.k * v2 + go * go);
    if (w.hasInner) slope -= ei.k * ei.k / (ei.k * ei.k * v2 + gi * gi);
    slope *= 0.5 * w.sigma;
    double next = slope > 0 ? t - f / slope : lo - 1;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const Azimuth vn{a.x + next * d.x, a.y + next * d.y};
    const double vv = dot(v, vn), goN = gDot(eo, vn);
    area += 0.5 * eo.k * atanStep((next - t) * eo.k * w.sigma, eo.k * eo.k * vv + go * goN);
    go = goN;
    if (w.hasInner) {
      const double giN = gDot(ei, vn);
      area -= 0.5 * ei.k * atanStep((next - t) * ei.k * w.sigma, ei.k * ei.k * vv + gi * giN);
      gi = giN;
    }
    t = next, v = vn;
  }

  // r² uniform between the wedge's edges at v; z² the same way, each without cancellation. r / |v| from
  // m_z² / |P|², so v need not be normalised; r² + z² = 1 to rounding at each edge, so neither does the
  // direction.
  const double v2 = dot(v, v);
  double rhoOuter2, zOuter2, rhoInner2 = 0, zInner2 = 1;
  radiusAt(eo, go, v2, rhoOuter2, zOuter2);
  if (w.hasInner) radiusAt(ei, gi, v2, rhoInner2, zInner2);
  const double s = u.y;
  const double rho = std::sqrt(std::max(0.0, (1 - s) * rhoInner2 + s * rhoOuter2));
  const double z = std::sqrt(std::max(0.0, (1 - s) * zInner2 + s * zOuter2));
  return ex * (rho * v.x) + ey * (rho * v.y) + ez * z;
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
