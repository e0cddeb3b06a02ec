// The geometry queries of the packet kernels: nearest hit and occlusion among the flat spheres and
// parallelograms, lane by lane as SceneGeometry computes them, or, when the scene's geometry is
// elsewhere (a BVH, loose triangles), handed to SceneGeometry one lane at a time (packet_queries.h).
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_GEOMETRY_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_GEOMETRY_INL_H_
#undef PENUMBRA_PACKET_GEOMETRY_INL_H_
#else
#define PENUMBRA_PACKET_GEOMETRY_INL_H_
#endif

#include <hwy/highway.h>
#include "core/geometry/parallelogram.h"
#include "core/render/packet_math-inl.h"
#include "core/render/packet_queries.h"
#include "core/render/packet_scene.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Sphere::mayHit.
HWY_INLINE MF sphereMayHit(const PacketSphere& s, const V3F& o, const V3F& d) {
  const V3F f{o.x - setF(s.center[0]), o.y - setF(s.center[1]), o.z - setF(s.center[2])};
  const VF a = dot(d, d), b = dot(f, d), ff = dot(f, f);
  return hn::Not(a * (ff - setF(s.radius * s.radius)) - b * b > setF(1e-5f) * a * ff);
}

// Sphere::roots after the pre-test `may`: t0 <= t1 in the lanes of `valid`.
struct Roots {
  VD t0, t1;
  MD valid;
};
HWY_INLINE Roots sphereRoots(const PacketSphere& s, const V3D& o, const V3D& d, MD may) {
  const V3D f{o.x - setD(double(s.center[0])), o.y - setD(double(s.center[1])),
              o.z - setD(double(s.center[2]))};
  const double r = s.radius;
  const VD a = dot(d, d);
  const VD invA = setD(1.0) / a;
  const VD b = dot(f, d);
  const VD bOverA = b * invA;
  const V3D v{f.x - bOverA * d.x, f.y - bOverA * d.y, f.z - bOverA * d.z};
  const VD disc = setD(r * r) - dot(v, v);
  const VD c = dot(f, f) - setD(r * r);
  const VD q = hn::Neg(b + hn::CopySign(hn::Sqrt(a * disc), b));
  const VD t1 = q * invA;
  const VD t0 = hn::IfThenElse(q != hn::Zero(DD()), c / q, t1);
  const MD swap = t0 > t1;
  return {hn::IfThenElse(swap, t1, t0), hn::IfThenElse(swap, t0, t1), hn::And(may, disc >= hn::Zero(DD()))};
}

// intersectParallelogram: the lanes hit in (tMin, tMax), with their t.
HWY_INLINE MF parallelogramHit(const Parallelogram& q, const V3F& o, const V3F& d, VF tMin, VF tMax, VF& t) {
  const V3F n = setF3(q.n);
  const VF denom = dot(n, d);
  const VF h = dot(n, o) - setF(q.planeOffset);
  const VF ndSum = hn::Abs(n.x * d.x) + hn::Abs(n.y * d.y) + hn::Abs(n.z * d.z);
  const VF noSum = hn::Abs(n.x * o.x) + hn::Abs(n.y * o.y) + hn::Abs(n.z * o.z);
  MF ok = hn::Abs(denom) > setF(detail::kParallelogramGamma3) * ndSum;
  ok =
      hn::And(ok, hn::Abs(h) > setF(detail::kParallelogramGamma7) * (noSum + setF(std::fabs(q.planeOffset))));
  t = hn::Neg(h) / denom;
  ok = hn::And(ok, hn::And(t > tMin, t < tMax));
  const V3F rel{(o.x - setF(q.p0.x)) + t * d.x, (o.y - setF(q.p0.y)) + t * d.y,
                (o.z - setF(q.p0.z)) + t * d.z};
  const VF u = dot(setF3(q.du), rel), v = dot(setF3(q.dv), rel);
  const VF zero = hn::Zero(DF()), one = setF(1.f);
  ok = hn::And(ok, hn::And(hn::And(u >= zero, u <= one), hn::And(v >= zero, v <= one)));
  return ok;
}

// SceneGeometry::occludedByFlatShapes for the lanes of `active` (tMin = 0): which are blocked.
HWY_INLINE MF occludedByFlatShapes(const PacketScene& scene, const V3F& o, const V3F& d, VF tMax,
                                   int32_t skipSphere, MF active) {
  const DF df;
  MF blocked = hn::FirstN(df, 0);
  const VF zero = hn::Zero(df);
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    if (static_cast<int32_t>(i) == skipSphere) continue;
    const MF may = hn::AndNot(blocked, hn::And(active, sphereMayHit(scene.spheres[i], o, d)));
    if (hn::AllFalse(df, may)) continue;
    const Roots r = sphereRoots(scene.spheres[i], promote(o), promote(d), toD(may));
    const VD tMinD = hn::Zero(DD()), tMaxD = promote(tMax);
    const MD in0 = hn::And(r.t0 > tMinD, r.t0 < tMaxD), in1 = hn::And(r.t1 > tMinD, r.t1 < tMaxD);
    blocked = hn::Or(blocked, toF(hn::And(r.valid, hn::Or(in0, in1))));
  }
  for (const PacketQuad& q : scene.quads) {
    if (hn::AllFalse(df, hn::AndNot(blocked, active))) break;
    VF t;
    blocked = hn::Or(blocked, hn::And(active, parallelogramHit(q.shape, o, d, zero, tMax, t)));
  }
  return blocked;
}

HWY_INLINE void storeF3(const V3F& v, float (&out)[3][kMaxPacketLanes]) {
  const DF df;
  hn::StoreU(v.x, df, out[0]);
  hn::StoreU(v.y, df, out[1]);
  hn::StoreU(v.z, df, out[2]);
}
HWY_INLINE V3F loadF3(const float (&v)[3][kMaxPacketLanes]) {
  const DF df;
  return {hn::LoadU(df, v[0]), hn::LoadU(df, v[1]), hn::LoadU(df, v[2])};
}
// The lanes where v is not 0 (the queries' 1/0 lanes).
HWY_INLINE MF loadMask(const float* v) {
  const DF df;
  return hn::LoadU(df, v) != hn::Zero(df);
}

// Segments from o along d up to tMax in the lanes of `active`, as the queries take them.
HWY_INLINE void storeSegments(const V3F& o, const V3F& d, VF tMax, MF active, PacketSegments& out) {
  const DF df;
  storeF3(o, out.o);
  storeF3(d, out.d);
  hn::StoreU(tMax, df, out.tMax);
  hn::StoreU(hn::IfThenElseZero(active, setF(1.f)), df, out.active);
}

// SceneGeometry::occluded(ray, skipSphere) for the lanes of `active` (tMin = 0): which are blocked.
HWY_INLINE MF occluded(const PacketScene& scene, const V3F& o, const V3F& d, VF tMax, int32_t skipSphere,
                       MF active) {
  if (!scene.geometryQueried) return occludedByFlatShapes(scene, o, d, tMax, skipSphere, active);
  const DF df;
  PacketSegments rays;
  storeSegments(o, d, tMax, active, rays);
  HWY_ALIGN float blocked[kMaxPacketLanes];
  queryOccluded(*scene.scene, rays, int(hn::Lanes(df)), skipSphere, blocked);
  return loadMask(blocked);
}

// The nearest surface along each lane's ray: a sphere's index, or a parallelogram's (which wins:
// SceneGeometry tests them after the spheres, bounded by the sphere's t), -1 for none, and its t.
struct Nearest {
  VF sphere, quad;
  VF t;
  MF quadHit, hit;
};

// SceneGeometry::intersect's loops over the flat spheres and parallelograms.
HWY_INLINE Nearest nearest(const PacketScene& scene, const V3F& o, const V3F& d, VF tMin, VF tMax) {
  const DF df;
  const VF none = setF(-1.f);
  Nearest n{none, none, tMax, hn::FirstN(df, 0), hn::FirstN(df, 0)};
  const V3D oD = promote(o), dD = promote(d);
  const VD tMinD = promote(tMin);
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const MF may = sphereMayHit(scene.spheres[i], o, d);
    if (hn::AllFalse(df, may)) continue;
    const Roots r = sphereRoots(scene.spheres[i], oD, dD, toD(may));
    const VD tMaxD = promote(n.t);
    const MD in0 = hn::And(r.t0 > tMinD, r.t0 < tMaxD), in1 = hn::And(r.t1 > tMinD, r.t1 < tMaxD);
    const MF hit = toF(hn::And(r.valid, hn::Or(in0, in1)));
    n.t = hn::IfThenElse(hit, demote(hn::IfThenElse(in0, r.t0, r.t1)), n.t);
    n.sphere = hn::IfThenElse(hit, setF(float(i)), n.sphere);
  }
  for (size_t j = 0; j < scene.quads.size(); ++j) {
    VF t;
    const MF hit = parallelogramHit(scene.quads[j].shape, o, d, tMin, n.t, t);
    n.t = hn::IfThenElse(hit, t, n.t);
    n.quad = hn::IfThenElse(hit, setF(float(j)), n.quad);
  }
  const VF zero = hn::Zero(df);
  n.quadHit = n.quad >= zero;
  n.hit = hn::Or(n.quadHit, n.sphere >= zero);
  return n;
}

// The lanes whose nearest surface is sphere i.
HWY_INLINE MF onSphere(const Nearest& n, size_t i) {
  return hn::AndNot(n.quadHit, n.sphere == setF(float(i)));
}

// Sphere::fillHit's point and normal for a hit at t along o + t·d (given in double as `along`).
HWY_INLINE void sphereHitPoint(const PacketSphere& s, const V3D& along, V3F& p, V3F& ng) {
  const V3D c{setD(double(s.center[0])), setD(double(s.center[1])), setD(double(s.center[2]))};
  V3D n{along.x - c.x, along.y - c.y, along.z - c.z};
  const VD len = hn::Sqrt(dot(n, n));
  const MD positive = len > hn::Zero(DD());
  const VD invLen = setD(1.0) / len;
  n = {hn::IfThenElseZero(positive, n.x * invLen), hn::IfThenElseZero(positive, n.y * invLen),
       hn::IfThenElse(positive, n.z * invLen, setD(1.0))};
  const VD r = setD(double(s.radius));
  p = demote(V3D{c.x + r * n.x, c.y + r * n.y, c.z + r * n.z});
  ng = demote(n);
}

// o + t·d in double, as the fill functions compute it.
HWY_INLINE V3D pointAlong(const V3F& o, const V3F& d, VF t) {
  const V3D oD = promote(o), dD = promote(d);
  const VD tD = promote(t);
  return {oD.x + tD * dD.x, oD.y + tD * dD.y, oD.z + tD * dD.z};
}

// What the camera rays hit, as ShadingPoint holds it, with the material's data.
struct PacketHit {
  MF hit;         // anything hit
  V3F p, ng, ns;  // ng and ns flipped to the ray's side (ShadingPoint)
  V3F nsHit;      // the shading normal as the geometry gives it (SurfaceHit::ns)
  VF offsetScale;
  MF shades;   // PacketObject::shades
  MF glossy;   // PacketObject::glossy (kept in scenes with a glossy material)
  MF emitter;  // PacketObject::emitter (kept for the light-share view)
  VF object;   // the index of the hit's object (material; kept as glossy)
  V3F albedoOverPi;
  V3F emitted;  // emittedAt
};

// The shading points of the lanes of m, for the queries.
HWY_INLINE void storeShading(const PacketHit& h, MF m, PacketShadingLanes& points) {
  storeF3(h.p, points.p);
  storeF3(h.ng, points.ng);
  storeF3(h.ns, points.ns);
  hn::StoreU(h.offsetScale, DF(), points.offsetScale);
  hn::StoreU(hn::IfThenElseZero(m, setF(1.f)), DF(), points.active);
}

HWY_INLINE void setObject(const PacketScene& scene, uint32_t index, MF m, const V3F& rayD,
                          const V3F& ngUnflipped, PacketHit& h) {
  const PacketObject& object = scene.objects[index];
  h.albedoOverPi = select(m, setF3(object.albedoOverPi), h.albedoOverPi);
  if (object.shades) h.shades = hn::Or(h.shades, m);
  // What only glossy scenes and the light-share view read.
  if (scene.anyGlossy) {
    if (object.glossy) h.glossy = hn::Or(h.glossy, m);
    h.object = hn::IfThenElse(m, setF(float(index)), h.object);
  }
  if (scene.lightShare && object.emitter) h.emitter = hn::Or(h.emitter, m);
  if (object.emits) {
    // SphereLight::eval: the outer side only.
    const MF facing = hn::And(m, dot(ngUnflipped, rayD) < hn::Zero(DF()));
    h.emitted = select(facing, setF3(object.radiance), h.emitted);
  }
}

// fillParallelogramHit's point: o + t·d moved onto the plane in double.
HWY_INLINE V3F quadHitPoint(const Parallelogram& q, const V3D& along) {
  const V3D qn{setD(double(q.n.x)), setD(double(q.n.y)), setD(double(q.n.z))};
  const VD off = dot(qn, along) - setD(double(q.planeOffset));
  return demote(V3D{along.x - qn.x * off, along.y - qn.y * off, along.z - qn.z * off});
}

// SceneGeometry::intersect's hit filling (fillParallelogramHit, Sphere::fillHit), emittedAt and the
// ShadingPoint's normals.
HWY_INLINE PacketHit fillHit(const PacketScene& scene, const Nearest& n, const V3F& o, const V3F& d) {
  const DF df;
  PacketHit h;
  const VF zero = hn::Zero(df);
  h.p = h.ng = h.ns = h.albedoOverPi = h.emitted = {zero, zero, zero};
  h.offsetScale = h.object = zero;
  h.shades = h.glossy = h.emitter = hn::FirstN(df, 0);
  h.hit = n.hit;
  const V3D along = pointAlong(o, d, n.t);
  for (size_t j = 0; j < scene.quads.size(); ++j) {
    const MF m = n.quad == setF(float(j));
    if (hn::AllFalse(df, m)) continue;
    const Parallelogram& q = scene.quads[j].shape;
    const V3F p = quadHitPoint(q, along);
    h.p = select(m, p, h.p);
    h.ng = select(m, setF3(q.n), h.ng);
    h.ns = select(m, setF3(q.ns), h.ns);
    h.offsetScale = hn::IfThenElse(m, maxAbs(p), h.offsetScale);
    setObject(scene, scene.quads[j].object, m, d, setF3(q.n), h);
    if (scene.quads[j].polygonLight >= 0) {
      // PolygonLight::eval: its emitting side only.
      const PacketPolygonLight& light = scene.polygons[size_t(scene.quads[j].polygonLight)];
      const MF facing = hn::And(m, dot(setF3(light.n), d) < zero);
      h.emitted = select(facing, setF3(light.radiance), h.emitted);
    }
  }
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const MF m = onSphere(n, i);
    if (hn::AllFalse(df, m)) continue;
    const PacketSphere& s = scene.spheres[i];
    V3F p, ng;
    sphereHitPoint(s, along, p, ng);
    h.p = select(m, p, h.p);
    h.ng = select(m, ng, h.ng);
    h.ns = select(m, ng, h.ns);
    h.offsetScale = hn::IfThenElse(m, maxOf(maxAbs(p), setF(s.offsetScale)), h.offsetScale);
    setObject(scene, s.object, m, d, ng, h);
  }
  h.nsHit = h.ns;
  // ShadingPoint: normals towards the viewer; a shading normal on the other side falls back to ng.
  const MF backFacing = dot(h.ng, d) > zero;
  h.ng = select(backFacing, V3F{hn::Neg(h.ng.x), hn::Neg(h.ng.y), hn::Neg(h.ng.z)}, h.ng);
  h.ns = select(backFacing, V3F{hn::Neg(h.ns.x), hn::Neg(h.ns.y), hn::Neg(h.ns.z)}, h.ns);
  h.ns = select(dot(h.ns, h.ng) < zero, h.ng, h.ns);
  return h;
}

// The camera rays' hits as the row loop queried them (queryCameraHits), in lanes.
HWY_INLINE PacketHit queriedHit(const PacketHitLanes& lanes) {
  const DF df;
  PacketHit h;
  h.hit = loadMask(lanes.hit);
  h.p = loadF3(lanes.p);
  h.ng = loadF3(lanes.ng);
  h.ns = loadF3(lanes.ns);
  h.nsHit = loadF3(lanes.nsHit);
  h.offsetScale = hn::LoadU(df, lanes.offsetScale);
  h.shades = loadMask(lanes.shades);
  h.glossy = loadMask(lanes.glossy);
  h.emitter = loadMask(lanes.emitter);
  h.object = hn::LoadU(df, lanes.object);
  h.albedoOverPi = loadF3(lanes.albedoOverPi);
  h.emitted = loadF3(lanes.emitted);
  return h;
}

// What each lane's camera ray hits (SceneGeometry::intersect and the ShadingPoint): the hits the row
// loop queried (`queried`) where the scene's rays are queried, else found in lanes.
HWY_INLINE PacketHit cameraHit(const PacketScene& scene, const PacketRays& rays,
                               const PacketHitLanes* queried) {
  if (scene.geometryQueried) return queriedHit(*queried);
  const DF df;
  const V3F o = loadF3(rays.o), d = loadF3(rays.d);
  return fillHit(scene, nearest(scene, o, d, hn::LoadU(df, rays.tMin), hn::LoadU(df, rays.tMax)), o, d);
}

// The light index forEachEmitterAlong gives lanes that reached a polygon light (any of them).
inline constexpr size_t kAnyPolygonLight = ~size_t(0);

// addEmitterAlong by the queries: add(light, lanes, Le, p, ng, index) once per sphere light that some
// lanes reach, and once for the lanes that reach polygon lights.
template <class Add>
HWY_INLINE void forEachQueriedEmitterAlong(const PacketScene& scene, const V3F& o, const V3F& w, MF active,
                                           const Add& add) {
  const DF df;
  PacketSegments rays;
  storeSegments(o, w, setF(INFINITY), active, rays);
  PacketEmitterLanes found;
  queryEmittersAlong(*scene.scene, rays, int(hn::Lanes(df)), found);
  const VF light = hn::LoadU(df, found.light);
  if (hn::AllFalse(df, light >= hn::Zero(df))) return;
  const V3F Le = loadF3(found.Le), p = loadF3(found.p), ng = loadF3(found.ng);
  // Each sphere light some lane reached, once; then the lanes that reached any polygon light together.
  const size_t lanes = hn::Lanes(df), spheres = scene.lights.size();
  for (size_t k = 0; k < lanes; ++k) {
    const float l = found.light[k];
    if (l < 0.f || size_t(l) >= spheres) continue;
    bool seen = false;
    for (size_t e = 0; e < k && !seen; ++e) seen = found.light[e] == l;
    if (!seen) add(size_t(l), light == setF(l), Le, p, ng, light);
  }
  const MF polygon = light >= setF(float(spheres));
  if (!hn::AllFalse(df, polygon)) add(kAnyPolygonLight, polygon, Le, p, ng, light);
}

// addEmitterAlong: for each lane of `active` whose ray (from o along unit w, tMin 0, no tMax) first
// reaches the front of an area light of non-black radiance, add(light, lanes, Le, p, ng, index) with that
// sphere light's index (kAnyPolygonLight for the lanes that reached polygon lights), those lanes, the
// radiance it sends back along w, the hit's point and (outward) normal there, and each lane's light as
// an index among the area lights (spheres, then polygons).
template <class Add>
HWY_INLINE void forEachEmitterAlong(const PacketScene& scene, const V3F& o, const V3F& w, MF active,
                                    const Add& add) {
  if (scene.geometryQueried) return forEachQueriedEmitterAlong(scene, o, w, active, add);
  const DF df;
  const VF zero = hn::Zero(df);
  const Nearest n = nearest(scene, o, w, zero, setF(INFINITY));
  const V3D along = pointAlong(o, w, n.t);
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const PacketObject& object = scene.objects[scene.spheres[i].object];
    if (!object.emits || !object.radianceNonBlack) continue;
    const MF m = hn::And(active, onSphere(n, i));
    if (hn::AllFalse(df, m)) continue;
    V3F p, ng;
    sphereHitPoint(scene.spheres[i], along, p, ng);
    const MF facing = hn::And(m, dot(ng, w) < zero);
    if (!hn::AllFalse(df, facing))
      add(size_t(object.light), facing, setF3(object.radiance), p, ng, setF(float(object.light)));
  }
  for (size_t j = 0; j < scene.quads.size(); ++j) {
    if (scene.quads[j].polygonLight < 0) continue;
    const PacketPolygonLight& light = scene.polygons[size_t(scene.quads[j].polygonLight)];
    if (light.radiance[0] == 0.f && light.radiance[1] == 0.f && light.radiance[2] == 0.f) continue;
    // PolygonLight::eval: its emitting side only.
    const MF facing = hn::And(hn::And(active, n.quad == setF(float(j))), dot(setF3(light.n), w) < zero);
    if (hn::AllFalse(df, facing)) continue;
    const Parallelogram& q = scene.quads[j].shape;
    add(kAnyPolygonLight, facing, setF3(light.radiance), quadHitPoint(q, along), setF3(q.n),
        setF(float(scene.lights.size() + size_t(scene.quads[j].polygonLight))));
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
