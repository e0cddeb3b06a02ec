// The projected solid angle's map of polygon lights in lanes: ProjectedPolygon (Nusselt's projection
// of the polygon onto the disk, wedges between vertex azimuths, the azimuth inverted by Newton's method
// with bisection) set up for each lane's light at its shading point and sampled, mirrored operation by
// operation in double; its atan2 is portableAtan2 (the same bits in lanes), and libm's hypot is called
// lane by lane on the lanes that need it. A polygon that reaches below the horizon of a lane's shading
// normal is clipped in that lane by the scalar map's own clip (its vertex count changes: up to five
// vertices, one edge on the horizon); everything after the clip runs in lanes.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_PROJECTED_POLYGON_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_PROJECTED_POLYGON_INL_H_
#undef PENUMBRA_PACKET_PROJECTED_POLYGON_INL_H_
#else
#define PENUMBRA_PACKET_PROJECTED_POLYGON_INL_H_
#endif

#include <hwy/highway.h>

#include <cmath>
#include <limits>

#include "core/lights/projected_polygon.h"
#include "core/render/packet_lights-inl.h"
#include "core/render/packet_math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// ProjectedPolygon's data in lanes: a wedge per slot, each lane's wedges in the scalar map's order with
// slots it does not use left empty (`real` false, area 0).
struct ProjectedPolygonLanes {
  // Five edges (a parallelogram clipped to the horizon) or four azimuth intervals, each halved at most
  // once.
  static constexpr int kVertices = ProjectedPolygon::kMaxVertices;
  static constexpr int kIntervals = kVertices, kSlots = 2 * kIntervals;
  struct EdgeLanes {
    VD k, gx, gy, p0, pd, alpha, beta;
  };
  struct WedgeLanes {
    VD ax, ay, dx, dy, sigma, area, start;  // start: the areas of the wedges before it
    EdgeLanes outer, inner;
    MD hasInner, real;
  };
  V3D origin, ex, ey, ez;
  V3D edgeNormals[kVertices];  // unit, in the local frame; zero past the clipped polygon's edges
  WedgeLanes wedges[kSlots];
  bool slotUsed[kSlots];  // real in some lane
  VD projectedSolidAngle;
  VF projected;  // Ω⊥ as LightTechnique rounds it (0 where nothing is sampled in lanes)
  MD inLanes;    // mapped in lanes with something to sample
};

namespace projected_polygon {

using EdgeLanes = ProjectedPolygonLanes::EdgeLanes;
using WedgeLanes = ProjectedPolygonLanes::WedgeLanes;

struct AzimuthLanes {
  VD x, y;
};

HWY_INLINE VD cross(const AzimuthLanes& a, const AzimuthLanes& b) {
  return a.x * b.y - a.y * b.x;
}
HWY_INLINE VD dot(const AzimuthLanes& a, const AzimuthLanes& b) {
  return a.x * b.x + a.y * b.y;
}
HWY_INLINE VD gDot(const EdgeLanes& e, const AzimuthLanes& v) {
  return e.gx * v.x + e.gy * v.y;
}
HWY_INLINE MD select(MD m, MD a, MD b) {
  return hn::Or(hn::And(m, a), hn::AndNot(m, b));
}
HWY_INLINE AzimuthLanes select(MD m, const AzimuthLanes& a, const AzimuthLanes& b) {
  return {hn::IfThenElse(m, a.x, b.x), hn::IfThenElse(m, a.y, b.y)};
}
HWY_INLINE EdgeLanes select(MD m, const EdgeLanes& a, const EdgeLanes& b) {
  return {hn::IfThenElse(m, a.k, b.k),      hn::IfThenElse(m, a.gx, b.gx),
          hn::IfThenElse(m, a.gy, b.gy),    hn::IfThenElse(m, a.p0, b.p0),
          hn::IfThenElse(m, a.pd, b.pd),    hn::IfThenElse(m, a.alpha, b.alpha),
          hn::IfThenElse(m, a.beta, b.beta)};
}
HWY_INLINE WedgeLanes select(MD m, const WedgeLanes& a, const WedgeLanes& b) {
  return {hn::IfThenElse(m, a.ax, b.ax),
          hn::IfThenElse(m, a.ay, b.ay),
          hn::IfThenElse(m, a.dx, b.dx),
          hn::IfThenElse(m, a.dy, b.dy),
          hn::IfThenElse(m, a.sigma, b.sigma),
          hn::IfThenElse(m, a.area, b.area),
          hn::IfThenElse(m, a.start, b.start),
          select(m, a.outer, b.outer),
          select(m, a.inner, b.inner),
          select(m, a.hasInner, b.hasInner),
          select(m, a.real, b.real)};
}
HWY_INLINE VD select(MD m, VD a, VD b) {
  return hn::IfThenElse(m, a, b);
}
// v[index] per lane (index a small whole number, below n).
template <class T>
HWY_INLINE T atIndex(VD index, const T* v, int n) {
  T r = v[0];
  for (int i = 1; i < n; ++i) r = select(index == setD(double(i)), v[i], r);
  return r;
}
HWY_INLINE V3D select(MD m, const V3D& a, const V3D& b) {
  return HWY_NAMESPACE::select(m, a, b);
}

// projected_polygon.cpp's atan2 (portableAtan2) in the lanes of m, 0 elsewhere.
HWY_INLINE VD atan2Lanes(MD m, VD y, VD x) {
  return hn::IfThenElseZero(m, portableAtan2Lanes(m, y, x));
}

// projected_polygon.cpp's pseudoAngle: grows with the counter-clockwise angle from ref to a.
HWY_INLINE VD pseudoAngle(const AzimuthLanes& ref, const AzimuthLanes& a) {
  const VD x = dot(ref, a), y = cross(ref, a);
  const VD q = y / (hn::Abs(x) + hn::Abs(y));
  return hn::IfThenElse(x >= hn::Zero(DD()), q,
                        hn::IfThenElse(y >= hn::Zero(DD()), setD(2.0) - q, setD(-2.0) - q));
}

// edgeOf: the boundary edge on the great circle with unit normal m.
HWY_INLINE EdgeLanes edgeOf(const V3D& m) {
  const VD zero = hn::Zero(DD());
  EdgeLanes e{hn::Abs(m.z), zero, zero, zero, zero, zero, zero};
  const VD sign = hn::IfThenElse(m.z < zero, setD(1.0), setD(-1.0));
  e.gx = sign * m.x;
  e.gy = sign * m.y;
  return e;
}

// placeEdge in the lanes of m: the edge's terms in a wedge from a to a + d, and its swept area.
HWY_INLINE VD placeEdge(MD m, EdgeLanes& e, const AzimuthLanes& a, const AzimuthLanes& d, VD sigma) {
  const VD zero = hn::Zero(DD());
  const VD ga = gDot(e, a);
  e.p0 = e.k * e.k + ga * ga;
  e.pd = e.k * e.k * dot(a, d) + ga * gDot(e, d);
  const VD area = setD(0.5) * e.k * atan2Lanes(m, e.k * sigma, e.p0 + e.pd);
  e.alpha = hn::IfThenElseZero(e.p0 > zero, setD(0.5) * e.k * e.k * sigma / e.p0);
  e.beta = hn::IfThenElseZero(area > zero, e.alpha / area - setD(1.0));
  return area;
}

// placeWedge in the lanes of m (`real` there, empty elsewhere): w the wedge from a to b.
HWY_INLINE void placeWedge(MD m, const AzimuthLanes& a, const AzimuthLanes& b, const EdgeLanes& outer,
                           const EdgeLanes& inner, MD hasInner, WedgeLanes& w) {
  const VD zero = hn::Zero(DD());
  const AzimuthLanes d{b.x - a.x, b.y - a.y};
  w.ax = a.x, w.ay = a.y, w.dx = d.x, w.dy = d.y;
  w.sigma = cross(a, d);
  w.outer = outer;
  w.inner = inner;
  w.hasInner = hasInner;
  w.real = m;
  VD area = placeEdge(m, w.outer, a, d, w.sigma);
  const MD withInner = hn::And(m, hasInner);
  area = hn::IfThenElse(withInner, area - placeEdge(withInner, w.inner, a, d, w.sigma), area);
  w.area = hn::IfThenElseZero(hn::And(m, zero < area), area);
}

// w a slot no lane uses (sampling reads only these two of its fields).
HWY_INLINE void clearWedge(WedgeLanes& w) {
  w.area = hn::Zero(DD());
  w.real = hn::FirstN(DD(), 0);
}

// atanStep of projected_polygon.cpp in the lanes of m: the series where the ratio is small, else atan2.
HWY_INLINE VD atanStep(MD m, VD y, VD x) {
  const MD series = hn::Abs(y) <= setD(0x1p-6) * x;
  const VD z = y / x, z2 = z * z;
  const VD s =
      z *
      (setD(1.0) + z2 * (setD(-1.0 / 3) + z2 * (setD(1.0 / 5) + z2 * (setD(-1.0 / 7) + z2 * setD(1.0 / 9)))));
  return hn::IfThenElse(series, s, atan2Lanes(hn::AndNot(series, m), y, x));
}

// radiusAt: r² / |v|² and z² of the edge's point at azimuth v.
HWY_INLINE void radiusAt(const EdgeLanes& e, VD gv, VD v2, VD& rho2, VD& z2) {
  const VD k2 = e.k * e.k, sum = k2 * v2 + gv * gv;
  const MD some = sum > hn::Zero(DD());
  rho2 = hn::IfThenElseZero(some, k2 / sum);
  z2 = hn::IfThenElse(some, gv * gv / sum, setD(1.0));
}

// ProjectedPolygon::AzimuthInterval in lanes: vertex and edge indices as whole numbers, -1 for none.
struct IntervalLanes {
  VD from, to, edgeA, edgeB;
};

// ProjectedPolygon::azimuthIntervals in lanes, without compaction: interval s lies between the s-th
// and (s+1)-th vertex in azimuth order, none where those two azimuths are equal or the polygon has
// fewer vertices (the non-empty ones keep the scalar function's order, so the wedges' cumulative sums,
// which add +0 for empty slots, are its sums). alpha[i] is vertex i's pseudo-angle, count the vertex
// count (3 to 5) per lane; writes out[0] to out[3].
HWY_INLINE void azimuthIntervals(const VD* alpha, VD count, IntervalLanes* out) {
  constexpr int kVertices = ProjectedPolygonLanes::kVertices;
  const VD zero = hn::Zero(DD()), one = setD(1.0), none = setD(-1.0);
  MD present[kVertices];
  for (int i = 0; i < kVertices; ++i) present[i] = count > setD(double(i));
  // The first lowest and first highest vertex (the scalar loop's strict comparisons).
  VD lo = zero, hi = zero, alphaLo = alpha[0], alphaHi = alpha[0];
  for (int i = 1; i < kVertices; ++i) {
    const MD lower = hn::And(present[i], alpha[i] < alphaLo),
             higher = hn::And(present[i], alpha[i] > alphaHi);
    lo = hn::IfThenElse(lower, setD(double(i)), lo);
    alphaLo = hn::IfThenElse(lower, alpha[i], alphaLo);
    hi = hn::IfThenElse(higher, setD(double(i)), hi);
    alphaHi = hn::IfThenElse(higher, alpha[i], alphaHi);
  }
  // The vertices in azimuth order, ties by index (the scalar insertion sort is stable): a sorting
  // network on (key, index), absent vertices keyed +∞ so that they sort last.
  VD key[kVertices], order[kVertices];
  for (int i = 0; i < kVertices; ++i) {
    key[i] = hn::IfThenElse(present[i], alpha[i], setD(INFINITY));
    order[i] = setD(double(i));
  }
  auto exchange = [&](int a, int b) {
    const MD swap = hn::Or(key[a] > key[b], hn::And(key[a] == key[b], order[a] > order[b]));
    const VD ka = key[a], oa = order[a];
    key[a] = hn::IfThenElse(swap, key[b], ka);
    key[b] = hn::IfThenElse(swap, ka, key[b]);
    order[a] = hn::IfThenElse(swap, order[b], oa);
    order[b] = hn::IfThenElse(swap, oa, order[b]);
  };
  static_assert(kVertices == 5, "the sorting network below sorts five");
  exchange(0, 3), exchange(1, 4), exchange(0, 2), exchange(1, 3), exchange(0, 1);
  exchange(2, 4), exchange(1, 2), exchange(3, 4), exchange(2, 3);
  // (i + 1) mod count and (i − 1) mod count of a vertex index i in [0, count).
  auto successor = [&](VD i) { return hn::IfThenElseZero(i + one < count, i + one); };
  auto predecessor = [&](VD i) { return hn::IfThenElse(i > zero, i - one, count - one); };
  for (int s = 0; s + 1 < kVertices; ++s) {
    const MD has = hn::And(present[s + 1], key[s + 1] > key[s]);
    IntervalLanes& r = out[s];
    r.from = hn::IfThenElse(has, order[s], none);
    r.to = hn::IfThenElse(has, order[s + 1], none);
    r.edgeA = r.edgeB = none;
    if (hn::AllFalse(DD(), has)) continue;
    const VD mid = setD(0.5) * (key[s] + key[s + 1]);
    // Chain A runs counter-clockwise from lo to hi (edge i from vertex i to i + 1), chain B clockwise
    // (edge i − 1 from vertex i to i − 1); each interval lies under the first edge of each chain whose
    // far end reaches mid, or under the chain's last edge.
    VD vertexA = lo, vertexB = lo;
    MD openA = has, openB = has;
    for (int c = 0; c < kVertices - 1; ++c) {
      const VD nextA = successor(vertexA);
      const MD takeA = hn::And(openA, hn::Or(atIndex(nextA, alpha, kVertices) >= mid, nextA == hi));
      r.edgeA = hn::IfThenElse(takeA, vertexA, r.edgeA);
      openA = hn::AndNot(takeA, openA);
      vertexA = nextA;
      const VD edgeB = predecessor(vertexB);
      const MD takeB = hn::And(openB, hn::Or(atIndex(edgeB, alpha, kVertices) >= mid, edgeB == hi));
      r.edgeB = hn::IfThenElse(takeB, edgeB, r.edgeB);
      openB = hn::AndNot(takeB, openB);
      vertexB = edgeB;
    }
  }
}

// ProjectedPolygon::clipToUpperHalfSpace in the lanes of `clip`, lane by lane (the clip changes the
// vertex count): the polygon pts (count vertices, edge normals m) into cp and cm, count updated. Other
// lanes keep theirs.
HWY_INLINE void clipLanes(MD clip, const V3D* pts, const V3D* m, V3D* cp, V3D* cm, VD& count) {
  constexpr int kVertices = ProjectedPolygonLanes::kVertices;
  const DD dd;
  HWY_ALIGN double in[2][4][3][kMaxPacketLanes], out[2][kVertices][3][kMaxPacketLanes];
  HWY_ALIGN double counts[kMaxPacketLanes], clipped[kMaxPacketLanes];
  for (int i = 0; i < 4; ++i) {
    const V3D* sources[2] = {&pts[i], &m[i]};
    for (int j = 0; j < 2; ++j) {
      hn::Store(sources[j]->x, dd, in[j][i][0]);
      hn::Store(sources[j]->y, dd, in[j][i][1]);
      hn::Store(sources[j]->z, dd, in[j][i][2]);
    }
  }
  hn::Store(count, dd, counts);
  hn::Store(hn::IfThenElseZero(clip, setD(1.0)), dd, clipped);
  for (size_t k = 0; k < hn::Lanes(dd); ++k) {
    DVec3 points[4], normals[4], outPoints[kVertices], outNormals[kVertices];
    int n = 0;
    if (clipped[k] != 0) {
      const int vertices = int(counts[k]);
      for (int i = 0; i < vertices; ++i) {
        points[i] = DVec3(in[0][i][0][k], in[0][i][1][k], in[0][i][2][k]);
        normals[i] = DVec3(in[1][i][0][k], in[1][i][1][k], in[1][i][2][k]);
      }
      n = ProjectedPolygon::clipToUpperHalfSpace(points, normals, vertices, outPoints, outNormals);
      counts[k] = n;
    }
    for (int i = 0; i < kVertices; ++i)
      for (int a = 0; a < 3; ++a) {
        out[0][i][a][k] = i < n ? outPoints[i][a] : 0.0;
        out[1][i][a][k] = i < n ? outNormals[i][a] : 0.0;
      }
  }
  for (int i = 0; i < kVertices; ++i) {
    const V3D p{hn::Load(dd, out[0][i][0]), hn::Load(dd, out[0][i][1]), hn::Load(dd, out[0][i][2])};
    const V3D q{hn::Load(dd, out[1][i][0]), hn::Load(dd, out[1][i][1]), hn::Load(dd, out[1][i][2])};
    cp[i] = HWY_NAMESPACE::select(clip, p, cp[i]);
    cm[i] = HWY_NAMESPACE::select(clip, q, cm[i]);
  }
  count = hn::IfThenElse(clip, hn::Load(dd, counts), count);
}

}  // namespace projected_polygon

// LightTechnique<ProjectedSolidAngle, PolygonLight>'s set-up (ProjectedPolygon::init) of each lane's
// polygon light seen from x with shading normal n, in the lanes of `active`, into c (written in place:
// it is kilobytes).
HWY_INLINE void projectedPolygon(const PolygonLanes& light, const V3F& x, const V3F& n, MF active,
                                 ProjectedPolygonLanes& c) {
  namespace pp = projected_polygon;
  using pp::AzimuthLanes;
  using pp::EdgeLanes;
  using pp::WedgeLanes;
  const DD dd;
  const VD zero = hn::Zero(dd), one = setD(1.0);
  constexpr int kIntervals = ProjectedPolygonLanes::kIntervals, kVertices = ProjectedPolygonLanes::kVertices;
  c.origin = promote(x);
  MD ok = validAndFacing(light, x, active);
  c.inLanes = hn::FirstN(dd, 0);
  c.projected = hn::Zero(DF());
  c.projectedSolidAngle = zero;
  for (bool& used : c.slotUsed) used = false;
  if (hn::AllFalse(dd, ok)) return;  // no lane sees the light's emitting side
  // The local frame: orthonormalBasis about the normalised normal.
  c.ez = normalized(promote(n));
  const VD sign = hn::CopySign(one, c.ez.z);
  const VD a = setD(-1.0) / (sign + c.ez.z);
  const VD b = c.ez.x * c.ez.y * a;
  c.ex = {one + sign * c.ez.x * c.ez.x * a, sign * b, hn::Neg(sign) * c.ez.x};
  c.ey = {b, sign + c.ez.y * c.ez.y * a, hn::Neg(c.ez.y)};
  auto toLocal = [&](const V3D& v) { return V3D{dot(v, c.ex), dot(v, c.ey), dot(v, c.ez)}; };

  // PolygonLight::vertices (in float) and each one's successor; slot 3 only for parallelograms.
  const MD quad = toD(light.parallelogram);
  V3F vf[4];
  vf[0] = light.p0;
  vf[1] = plus(light.p0, light.e1);
  vf[3] = plus(light.p0, light.e2);
  vf[2] = HWY_NAMESPACE::select(light.parallelogram, plus(vf[1], light.e2), vf[3]);
  V3D vd[4], rel[4], edges[4];
  for (int i = 0; i < 4; ++i) vd[i] = promote(vf[i]);
  for (int i = 0; i < 4; ++i) {
    const V3D next = i == 2 ? pp::select(quad, vd[3], vd[0]) : vd[(i + 1) % 4];
    rel[i] = toLocal(minus(vd[i], c.origin));
    edges[i] = toLocal(minus(next, vd[i]));
  }
  const V3D planeNormal = cross(edges[0], edges[1]);
  const VD side = dot(rel[0], planeNormal);
  ok = hn::And(ok, side * side > setD(1e-24) * dot(rel[0], rel[0]) * dot(planeNormal, planeNormal));
  // Wound so that the inside is where m · w ≥ 0: forward, or (0, n−1, ..., 1) with each edge reversed.
  const MD forward = side > zero;
  auto negated = [](const V3D& v) { return V3D{hn::Neg(v.x), hn::Neg(v.y), hn::Neg(v.z)}; };
  const V3D reversedPts[4] = {rel[0], pp::select(quad, rel[3], rel[2]), pp::select(quad, rel[2], rel[1]),
                              rel[1]};
  const V3D reversedEdges[4] = {pp::select(quad, edges[3], edges[2]), pp::select(quad, edges[2], edges[1]),
                                pp::select(quad, edges[1], edges[0]), edges[0]};
  V3D pts[4], m[4];
  for (int i = 0; i < 4; ++i) {
    pts[i] = pp::select(forward, rel[i], reversedPts[i]);
    m[i] = pp::select(forward, cross(rel[i], edges[i]), cross(reversedPts[i], negated(reversedEdges[i])));
  }
  // Clipped to the upper half space: a polygon with every vertex on or above the horizon is kept as it
  // is; one reaching below it is clipped lane by lane.
  V3D cp[kVertices], cm[kVertices];
  for (int i = 0; i < 4; ++i) cp[i] = pts[i], cm[i] = m[i];
  cp[4] = cm[4] = V3D{zero, zero, zero};
  VD count = hn::IfThenElse(quad, setD(4.0), setD(3.0));
  MD above = hn::And(pts[0].z >= zero, hn::And(pts[1].z >= zero, pts[2].z >= zero));
  above = hn::And(above, hn::Or(hn::Not(quad), pts[3].z >= zero));
  const MD clip = hn::AndNot(above, ok);
  if (!hn::AllFalse(dd, clip)) pp::clipLanes(clip, pts, m, cp, cm, count);
  ok = hn::And(ok, count >= setD(3.0));
  if (hn::AllFalse(dd, ok)) return;

  // Unit edge normals, the zenith's side, the vertices' unit azimuths.
  V3D en[kVertices];
  AzimuthLanes az[kVertices];
  MD hasAzimuth[kVertices], present[kVertices];
  MD zenithInside = hn::Not(hn::FirstN(dd, 0));
  for (int i = 0; i < kVertices; ++i) {
    present[i] = count > setD(double(i));
    const VD len2 = dot(cm[i], cm[i]);
    const MD nonZero = len2 > zero;
    const V3D unit = scaled(cm[i], one / hn::Sqrt(len2));
    en[i] = {hn::IfThenElseZero(nonZero, unit.x), hn::IfThenElseZero(nonZero, unit.y),
             hn::IfThenElseZero(nonZero, unit.z)};
    c.edgeNormals[i] = {hn::IfThenElseZero(present[i], en[i].x), hn::IfThenElseZero(present[i], en[i].y),
                        hn::IfThenElseZero(present[i], en[i].z)};
    zenithInside = hn::AndNot(hn::And(present[i], en[i].z < zero), zenithInside);
    const VD r2 = cp[i].x * cp[i].x + cp[i].y * cp[i].y;
    hasAzimuth[i] = r2 > zero;
    const VD inv = hn::IfThenElseZero(hasAzimuth[i], one / hn::Sqrt(r2));
    az[i] = {hn::IfThenElse(hasAzimuth[i], cp[i].x * inv, one),
             hn::IfThenElseZero(hasAzimuth[i], cp[i].y * inv)};
  }

  // Where the zenith is outside: the vertices' pseudo-angles about the sum of their azimuths, and each
  // lane's wedges between consecutive azimuths.
  AzimuthLanes ref{zero, zero};
  for (int i = 0; i < kVertices; ++i)
    ref = pp::select(present[i], AzimuthLanes{ref.x + az[i].x, ref.y + az[i].y}, ref);
  const MD outside = hn::AndNot(zenithInside, ok);
  ok = hn::AndNot(hn::AndNot(ref.x * ref.x + ref.y * ref.y > zero, outside), ok);
  VD alpha[kVertices];
  for (int i = 0; i < kVertices; ++i) alpha[i] = pp::pseudoAngle(ref, az[i]);
  const VD none = setD(-1.0);
  pp::IntervalLanes intervals[kIntervals];
  for (pp::IntervalLanes& interval : intervals) interval = {none, none, none, none};
  if (!hn::AllFalse(dd, hn::And(ok, outside))) pp::azimuthIntervals(alpha, count, intervals);

  // addWedge per interval: one wedge, or two halves when it spans more than 3π/4.
  for (int s = 0; s < kIntervals; ++s) {
    // The zenith inside: the wedge from vertex s to its successor, under edge s.
    const VD next = hn::IfThenElseZero(count > setD(double(s + 1)), setD(double(s + 1)));
    const AzimuthLanes insideTo = pp::atIndex(next, az, kVertices);
    const MD insideHasTo = pp::atIndex(next, hasAzimuth, kVertices);
    const MD insideReal = hn::And(hn::And(zenithInside, present[s]), hn::And(hasAzimuth[s], insideHasTo));
    // The zenith outside: between two consecutive azimuths, under one edge of each chain.
    const VD fromIndex = intervals[s].from, toIndex = intervals[s].to;
    const MD outsideReal = hn::And(outside, fromIndex >= zero);
    MD placed = hn::And(ok, pp::select(zenithInside, insideReal, outsideReal));
    if (hn::AllFalse(dd, placed)) {
      pp::clearWedge(c.wedges[2 * s]);
      pp::clearWedge(c.wedges[2 * s + 1]);
      continue;
    }
    const AzimuthLanes outsideFrom = pp::atIndex(fromIndex, az, kVertices);
    const AzimuthLanes outsideTo = pp::atIndex(toIndex, az, kVertices);
    const EdgeLanes ea = pp::edgeOf(pp::atIndex(intervals[s].edgeA, en, kVertices));
    const EdgeLanes eb = pp::edgeOf(pp::atIndex(intervals[s].edgeB, en, kVertices));
    const AzimuthLanes um{outsideFrom.x + outsideTo.x, outsideFrom.y + outsideTo.y};
    const MD aOuter = ea.k * hn::Abs(pp::gDot(eb, um)) >= eb.k * hn::Abs(pp::gDot(ea, um));

    const AzimuthLanes from = pp::select(zenithInside, az[s], outsideFrom);
    const AzimuthLanes to = pp::select(zenithInside, insideTo, outsideTo);
    const EdgeLanes outer = pp::select(zenithInside, pp::edgeOf(en[s]), pp::select(aOuter, ea, eb));
    const EdgeLanes inner = pp::select(aOuter, eb, ea);
    const MD hasInner = hn::Not(zenithInside);
    placed = hn::And(placed, pp::cross(from, to) > zero);
    const MD halved = hn::And(placed, pp::dot(from, to) < setD(-0.70710678118654752));
    if (hn::AllFalse(dd, halved)) {
      pp::placeWedge(placed, from, to, outer, inner, hasInner, c.wedges[2 * s]);
      pp::clearWedge(c.wedges[2 * s + 1]);
      continue;
    }
    const VD bx = to.y - from.y, by = from.x - to.x;
    const VD inv = one / libmLanes(halved, bx, by, [](double u, double v) { return std::hypot(u, v); });
    const AzimuthLanes mid{bx * inv, by * inv};
    pp::placeWedge(placed, from, pp::select(halved, mid, to), outer, inner, hasInner, c.wedges[2 * s]);
    pp::placeWedge(halved, mid, to, outer, inner, hasInner, c.wedges[2 * s + 1]);
  }

  // The wedges' cumulative areas in order (an empty slot adds +0: the scalar map's sums).
  VD total = zero;
  for (int s = 0; s < ProjectedPolygonLanes::kSlots; ++s) {
    c.wedges[s].start = total;
    total = total + c.wedges[s].area;
    c.slotUsed[s] = !hn::AllFalse(dd, c.wedges[s].real);
  }
  c.projectedSolidAngle = total;
  ok = hn::And(ok, hn::And(total > zero, total < setD(INFINITY)));
  // LightTechnique keeps Ω⊥ as a float and samples only where that is positive.
  c.projected = demote(hn::IfThenElseZero(ok, total));
  c.inLanes = hn::And(ok, toD(c.projected > hn::Zero(DF())));
  c.projected = hn::IfThenElseZero(toF(c.inLanes), c.projected);
}

// ProjectedPolygon::pdfDirection of unit direction w in the lanes of c.inLanes (0 elsewhere): cos θ / Ω⊥
// inside the polygon, to 1e-12 outside each edge.
HWY_INLINE VD pdfProjectedPolygon(const ProjectedPolygonLanes& c, const V3D& w) {
  const VD zero = hn::Zero(DD());
  const VD z = dot(w, c.ez);
  const V3D local{dot(w, c.ex), dot(w, c.ey), z};
  MD inside = hn::And(c.inLanes, z > zero);
  for (const V3D& m : c.edgeNormals) inside = hn::AndNot(dot(m, local) < setD(-1e-12), inside);
  return hn::IfThenElseZero(inside, z / c.projectedSolidAngle);
}

// ProjectedPolygon::sampleDirection in the lanes of c.inLanes: the unit direction for (u0, u1).
HWY_INLINE V3D sampleProjectedPolygon(const ProjectedPolygonLanes& c, VF u0, VF u1) {
  namespace pp = projected_polygon;
  using pp::AzimuthLanes;
  const DD dd;
  const VD zero = hn::Zero(dd), one = setD(1.0);
  const VD target = promote(u0) * c.projectedSolidAngle;
  // The last wedge that starts at or below the target (some slot is used where any lane samples).
  int first = 0;
  while (first + 1 < ProjectedPolygonLanes::kSlots && !c.slotUsed[first]) ++first;
  ProjectedPolygonLanes::WedgeLanes w = c.wedges[first];
  for (int s = first + 1; s < ProjectedPolygonLanes::kSlots; ++s) {
    if (!c.slotUsed[s]) continue;
    w = pp::select(hn::And(c.wedges[s].real, c.wedges[s].start <= target), c.wedges[s], w);
  }
  const pp::EdgeLanes &eo = w.outer, &ei = w.inner;
  const VD shifted = target - w.start;
  const VD tau = hn::IfThenElse(shifted < zero, zero, hn::IfThenElse(w.area < shifted, w.area, shifted));

  // The first λ: the model's root in [0, 1], else λ proportional to τ.
  VD t = hn::IfThenElseZero(w.area > zero, tau / w.area);
  {
    const VD ao = eo.alpha, bo = eo.beta;
    const VD ai = hn::IfThenElseZero(w.hasInner, ei.alpha), bi = hn::IfThenElseZero(w.hasInner, ei.beta);
    const VD c2 = tau * bo * bi - ao * bi + ai * bo, c1 = tau * (bo + bi) - ao + ai;
    const VD disc = c1 * c1 - setD(4.0) * c2 * tau;
    const VD q = setD(-0.5) * (c1 + hn::CopySign(hn::Sqrt(disc), c1));
    const VD r1 = tau / q, r2 = q / c2;
    const MD solved = disc >= zero;
    const MD r1In = hn::And(solved, hn::And(r1 >= zero, r1 <= one));
    const MD r2In = hn::AndNot(r1In, hn::And(solved, hn::And(r2 >= zero, r2 <= one)));
    t = hn::IfThenElse(r1In, r1, hn::IfThenElse(r2In, r2, t));
  }
  // Against the horizon: two Newton steps on the cubic with the wedge's area and end slopes.
  const MD horizon = hn::And(c.inLanes, hn::And(eo.gx == zero, eo.gy == zero));
  if (!hn::AllFalse(dd, horizon)) {
    const AzimuthLanes v1{w.ax + w.dx, w.ay + w.dy};
    const VD q1 = pp::dot(v1, v1), go1 = pp::gDot(eo, v1);
    VD s1 = eo.k * eo.k / (eo.k * eo.k * q1 + go1 * go1);
    const VD gi1 = pp::gDot(ei, v1);
    s1 = hn::IfThenElse(w.hasInner, s1 - ei.k * ei.k / (ei.k * ei.k * q1 + gi1 * gi1), s1);
    s1 = s1 * (setD(0.5) * w.sigma);
    const VD s0 = eo.alpha - hn::IfThenElseZero(w.hasInner, ei.alpha), a1 = w.area;
    const MD steep = hn::And(horizon, hn::Or(s0 < setD(1e-2) * a1, s1 < setD(1e-2) * a1));
    const VD h2 = setD(3.0) * a1 - setD(2.0) * s0 - s1, h3 = s0 + s1 - setD(2.0) * a1;
    for (int k = 0; k < 2; ++k) {
      const VD h = t * (s0 + t * (h2 + t * h3)) - tau, dh = s0 + t * (setD(2.0) * h2 + setD(3.0) * t * h3);
      const VD next = hn::IfThenElse(dh > zero, t - h / dh, setD(-1.0));
      t = hn::IfThenElse(hn::And(steep, hn::And(next >= zero, next <= one)), next, t);
    }
  }

  // Newton's method on the wedge's area below v(λ), safeguarded by bisection.
  VD lo = zero, hi = one;
  const VD tolerance = setD(ProjectedPolygon::kAreaTolerance) * w.area;
  const VD ulps = setD(4 * std::numeric_limits<double>::epsilon());
  const VD halfKo = setD(0.5) * eo.k, halfKi = setD(0.5) * ei.k;
  const VD ko2 = eo.k * eo.k, ki2 = ei.k * ei.k;
  AzimuthLanes v{w.ax + t * w.dx, w.ay + t * w.dy};
  VD go = pp::gDot(eo, v), gi = hn::IfThenElseZero(w.hasInner, pp::gDot(ei, v));
  const MD withInner = hn::And(c.inLanes, w.hasInner);
  VD area = halfKo * pp::atan2Lanes(c.inLanes, t * eo.k * w.sigma, eo.p0 + t * eo.pd);
  area = hn::IfThenElse(
      withInner, area - halfKi * pp::atan2Lanes(withInner, t * ei.k * w.sigma, ei.p0 + t * ei.pd), area);
  MD running = c.inLanes;
  for (int step = 0; step < ProjectedPolygon::kMaxInversionSteps; ++step) {
    const VD f = area - tau;
    running = hn::AndNot(hn::Abs(f) <= tolerance, running);
    const MD below = f < zero;
    lo = hn::IfThenElse(hn::And(running, below), t, lo);
    hi = hn::IfThenElse(hn::AndNot(below, running), t, hi);
    running = hn::And(running, hi - lo > ulps);
    if (hn::AllFalse(dd, running)) break;
    const VD v2 = pp::dot(v, v);
    VD slope = ko2 / (ko2 * v2 + go * go);
    slope = hn::IfThenElse(w.hasInner, slope - ki2 / (ki2 * v2 + gi * gi), slope);
    slope = slope * (setD(0.5) * w.sigma);
    VD next = hn::IfThenElse(slope > zero, t - f / slope, lo - one);
    next = hn::IfThenElse(hn::And(next > lo, next < hi), next, setD(0.5) * (lo + hi));
    const AzimuthLanes vn{w.ax + next * w.dx, w.ay + next * w.dy};
    const VD vv = pp::dot(v, vn), goN = pp::gDot(eo, vn), giN = pp::gDot(ei, vn);
    const VD advance = next - t;
    VD stepped = area + halfKo * pp::atanStep(running, advance * eo.k * w.sigma, ko2 * vv + go * goN);
    const MD runningInner = hn::And(running, w.hasInner);
    stepped = hn::IfThenElse(
        w.hasInner,
        stepped - halfKi * pp::atanStep(runningInner, advance * ei.k * w.sigma, ki2 * vv + gi * giN),
        stepped);
    area = hn::IfThenElse(running, stepped, area);
    go = hn::IfThenElse(running, goN, go);
    gi = hn::IfThenElse(runningInner, giN, gi);
    t = hn::IfThenElse(running, next, t);
    v = pp::select(running, vn, v);
  }

  // r² and z² uniform between the wedge's edges at v.
  const VD v2 = pp::dot(v, v);
  VD rhoOuter2, zOuter2, rhoInner2, zInner2;
  pp::radiusAt(eo, go, v2, rhoOuter2, zOuter2);
  pp::radiusAt(ei, gi, v2, rhoInner2, zInner2);
  rhoInner2 = hn::IfThenElseZero(w.hasInner, rhoInner2);
  zInner2 = hn::IfThenElse(w.hasInner, zInner2, one);
  const VD s = promote(u1);
  const VD rhoMix = (one - s) * rhoInner2 + s * rhoOuter2, zMix = (one - s) * zInner2 + s * zOuter2;
  const VD rho = hn::Sqrt(hn::IfThenElseZero(zero < rhoMix, rhoMix));
  const VD z = hn::Sqrt(hn::IfThenElseZero(zero < zMix, zMix));
  const VD x = rho * v.x, y = rho * v.y;
  return {c.ex.x * x + c.ey.x * y + c.ez.x * z, c.ex.y * x + c.ey.y * y + c.ez.y * z,
          c.ex.z * x + c.ey.z * y + c.ez.z * z};
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
