// The light-sampling techniques of sphere lights in the packet kernels (LightTechnique<measure,
// SphereLight> in lanes): by area and solid angle through packet_lights-inl.h; by the projected solid
// angle through ProjectedSphereCap, mirrored lane by lane: a cap wholly above a lane's horizon is set
// up and sampled in lanes (its map is the concentric disk scaled onto an ellipse, in closed form); a
// cap that straddles the horizon (whose maps need arcsines and an iterative inversion) or whose centre
// lies along the normal (whose frame comes from orthonormalBasis) is left to the scalar cap, lane by
// lane, for those lanes only.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_SPHERE_TECHNIQUES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_SPHERE_TECHNIQUES_INL_H_
#undef PENUMBRA_PACKET_SPHERE_TECHNIQUES_INL_H_
#else
#define PENUMBRA_PACKET_SPHERE_TECHNIQUES_INL_H_
#endif

#include <hwy/highway.h>

#include "core/lights/projected_cap.h"
#include "core/render/packet_bsdf-inl.h"
#include "core/render/packet_geometry-inl.h"
#include "core/render/packet_lights-inl.h"
#include "core/render/packet_math-inl.h"
#include "core/render/packet_queries.h"
#include "core/render/packet_scalar_samples-inl.h"
#include "core/render/packet_scene.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// std::sqrt(std::max(v, 0.0)) (projected_cap.cpp's sqrtNonNeg): NaN stays NaN as there.
HWY_INLINE VD sqrtNonNeg(VD v) {
  const VD zero = hn::Zero(DD());
  return hn::Sqrt(hn::IfThenElse(v < zero, zero, v));
}

// ProjectedSphereCap::init of one sphere light at each lane's shading point, for the ellipse map.
struct ProjectedCapLanes {
  V3D origin, toCenter, ex, ey, ez;
  VD d2, distance, sinAlpha, xc, a, b, k;
  VD invProjectedSolidAngle;
  VF projected;  // Ω⊥ as LightTechnique rounds it (0 where nothing is sampled in lanes)
  MD inLanes;    // set up in lanes with something to sample
  MF byScalar;   // left to the scalar cap: straddling the horizon, or no frame from the cross product
};

HWY_INLINE ProjectedCapLanes projectedCap(const PacketLight& light, const V3F& x, const V3F& n, MF active) {
  const DD dd;
  const VD zero = hn::Zero(dd);
  const VD r = setD(double(light.radius));
  ProjectedCapLanes c;
  c.origin = promote(x);
  c.toCenter = {setD(double(light.center[0])) - c.origin.x, setD(double(light.center[1])) - c.origin.y,
                setD(double(light.center[2])) - c.origin.z};
  c.ez = promote(n);
  const V3D side = cross(c.ez, c.toCenter);
  c.d2 = dot(c.toCenter, c.toCenter);
  const VD side2 = dot(side, side);
  const VD d = hn::Sqrt(c.d2), sideLength = hn::Sqrt(side2), tangentLength = sqrtNonNeg(c.d2 - r * r);
  c.distance = d;
  // Outside the light at a finite distance (the light's radius is positive: kernels skip it otherwise).
  MD ok = hn::And(toD(active), hn::And(d >= r, d < setD(INFINITY)));
  const VD invD = setD(1.0) / d;
  c.sinAlpha = r * invD;
  const VD cosAlpha = tangentLength * invD;
  const VD cosCentre = dot(c.toCenter, c.ez) * invD;
  ok = hn::AndNot(cosCentre <= hn::Neg(c.sinAlpha), ok);  // entirely below the horizon
  const VD sinCentre = sideLength * invD;
  const VD invSideLength = setD(1.0) / sideLength;
  c.ey = {side.x * invSideLength, side.y * invSideLength, side.z * invSideLength};
  c.ex = cross(c.ey, c.ez);
  c.xc = cosAlpha * sinCentre;
  c.a = c.sinAlpha * cosCentre;
  c.b = c.sinAlpha;
  c.k = c.sinAlpha * c.sinAlpha + cosAlpha * cosAlpha * cosCentre * cosCentre;
  const MD straddling = cosCentre < c.sinAlpha;
  const MD scalar = hn::And(ok, hn::Or(straddling, hn::Not(sideLength > zero)));
  c.byScalar = toF(scalar);
  // The ellipse's area π a b: sphere_cap.h's first case.
  const VD area = setD(kPiD) * c.a * c.b;
  c.inLanes = hn::And(hn::AndNot(scalar, ok), area >= setD(ProjectedSphereCap::kMinProjectedSolidAngle));
  c.invProjectedSolidAngle = setD(1.0) / area;
  c.projected = demote(hn::IfThenElseZero(c.inLanes, area));
  return c;
}

// ProjectedSphereCap::sample on the ellipse map (Peters & Dachsbacher's affine image of the concentric
// disk, lifted by Nusselt's analogy), in the lanes of c.inLanes.
HWY_INLINE PacketLightSample sampleProjectedCap(const PacketLight& light, const ProjectedCapLanes& c, VF u0,
                                                VF u1) {
  const DiskPointF disk = concentricPoint(u0, u1);
  const VD dx = c.a * promote(disk.x), y = c.b * promote(disk.y);
  const VD z = sqrtNonNeg(c.k - y * y - dx * (setD(2.0) * c.xc + dx));
  const VD along = c.xc + dx;
  const V3D w{along * c.ex.x + y * c.ey.x + z * c.ez.x, along * c.ex.y + y * c.ey.y + z * c.ez.y,
              along * c.ex.z + y * c.ey.z + z * c.ez.z};
  // The near intersection with the sphere, as ProjectedSphereCap::sample computes it.
  const VD r = setD(double(light.radius));
  const VD tca = dot(w, c.toCenter);
  const V3D perp{c.toCenter.x - tca * w.x, c.toCenter.y - tca * w.y, c.toCenter.z - tca * w.z};
  const VD h = sqrtNonNeg(r * r - dot(perp, perp));
  const VD dist = (c.d2 - r * r) / (tca + h);
  PacketLightSample s;
  s.wi = demote(w);
  s.dist = demote(dist);
  s.pdf = demote(z * c.invProjectedSolidAngle);
  s.projected = c.projected;
  s.valid = hn::And(toF(c.inLanes), s.pdf > hn::Zero(DF()));
  return s;
}

// ProjectedSphereCap::pdf (the float direction's, with its cap test widened by kDirectionSlack) of unit
// direction wF in the lanes of c.inLanes, 0 elsewhere.
HWY_INLINE VF pdfProjectedCap(const ProjectedCapLanes& c, const V3F& wF) {
  const VD zero = hn::Zero(DD());
  const V3D w = promote(wF);
  const VD len2 = dot(w, w);
  const V3D x = cross(w, c.toCenter);
  const VD sinMax = c.sinAlpha + setD(ProjectedSphereCap::kDirectionSlack);
  const VD cosTheta = dot(w, c.ez) / hn::Sqrt(len2);
  const MD inside = hn::And(hn::And(c.inLanes, len2 > zero),
                            hn::And(hn::Not(dot(w, c.toCenter) <= zero),
                                    hn::Not(dot(x, x) > sinMax * sinMax * len2 * c.distance * c.distance)));
  return demote(hn::IfThenElseZero(hn::And(inside, cosTheta > zero), cosTheta * c.invProjectedSolidAngle));
}

// LightTechnique<ProjectedSolidAngle, SphereLight> of one light at the shading points of a packet's
// lanes `active`, for draws before drawEnd: set up once, then sampled per draw (sample) or asked a
// direction's density (pdf); the lanes left to the scalar cap get theirs from the scalar technique.
struct ProjectedCapTechnique {
  const PacketLight& light;
  ProjectedCapLanes cap;
  ScalarLightSamples<LightMeasure::ProjectedSolidAngle> scalar;

  ProjectedCapTechnique(const PacketScene& s, size_t l, const PacketHit& h, MF active, size_t drawEnd)
      : light(s.lights[l]),
        cap(projectedCap(light, h.p, h.ns, active)),
        scalar(s, broadcastIndex(l).data(), h, cap.byScalar, drawEnd) {}

  PacketLightSample sample(const PacketDraws& draws, size_t j) const {
    VF u0, u1;
    loadDraw(draws, j, u0, u1);
    return scalar.merge(draws, j, sampleProjectedCap(light, cap, u0, u1));
  }

  // The density of unit direction w, which reached the light at p with normal n.
  VF pdf(const V3F& w, const V3F& p, const V3F& n) const {
    return scalar.mergePdf(w, p, n, pdfProjectedCap(cap, w));
  }
};

// LightTechnique<kMeasure, SphereLight> of sphere light l at the shading points of a packet's lanes
// `active`, for draws before drawEnd: sample(draws, j) draws the light sample of draw j in every lane, pdf(w,
// p, n) is the density of a direction w that reached the light at p with normal n.
template <LightMeasure kMeasure>
struct SphereTechnique {
  const PacketLight& light;
  V3F x;
  SphereTechnique(const PacketScene& scene, size_t l, const PacketHit& h, MF /*active*/, size_t /*drawEnd*/)
      : light(scene.lights[l]), x(h.p) {}
  PacketLightSample sample(const PacketDraws& draws, size_t j) const {
    VF u0, u1;
    loadDraw(draws, j, u0, u1);
    return kMeasure == LightMeasure::Area ? sampleArea(light, x, u0, u1) : sampleSolidAngle(light, x, u0, u1);
  }
  VF pdf(const V3F& w, const V3F& p, const V3F& n) const {
    return kMeasure == LightMeasure::Area ? pdfAreaAsSolidAngle(light, x, p, n) : pdfSolidAngle(light, x, w);
  }
};
template <>
struct SphereTechnique<LightMeasure::ProjectedSolidAngle> : ProjectedCapTechnique {
  using ProjectedCapTechnique::ProjectedCapTechnique;
};

// A sphere light the kernels sample: one of non-black radiance and positive size (the others' draws
// are skipped, as the scalar techniques skip them).
HWY_INLINE bool sampled(const PacketLight& light) {
  return !light.black && light.radius > 0.f;
}
}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
