// The light-sampling techniques of polygon lights in the packet kernels (LightTechnique<measure,
// PolygonLight> in lanes), of one light broadcast to every lane or of each lane's own: by area in lanes
// (samplePolygonArea); by the solid angle in lanes on the spherical triangles' and rectangles' maps
// (packet_spherical_polygons-inl.h); by the projected solid angle in lanes on the clipped polygon's map
// (packet_projected_polygon-inl.h, clipped to each lane's horizon); the rest (sheared parallelograms
// and polygons too small for the maps by the solid angle) by the scalar techniques lane by lane
// (ScalarLightSamples), the rest of each draw (shadow ray, reflection, weights, sums) in lanes.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_POLYGON_TECHNIQUES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_POLYGON_TECHNIQUES_INL_H_
#undef PENUMBRA_PACKET_POLYGON_TECHNIQUES_INL_H_
#else
#define PENUMBRA_PACKET_POLYGON_TECHNIQUES_INL_H_
#endif

#include <hwy/highway.h>

#include <cfloat>
#include <type_traits>

#include "core/render/packet_bsdf-inl.h"
#include "core/render/packet_geometry-inl.h"
#include "core/render/packet_lights-inl.h"
#include "core/render/packet_math-inl.h"
#include "core/render/packet_projected_polygon-inl.h"
#include "core/render/packet_scalar_samples-inl.h"
#include "core/render/packet_scene.h"
#include "core/render/packet_spherical_polygons-inl.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The techniques' floatDensity: a density as a float, 0 where it is not positive or does not fit.
HWY_INLINE VF floatDensity(VD pdf) {
  return demote(hn::IfThenElseZero(hn::And(pdf > hn::Zero(DD()), pdf < setD(3.4e38)), pdf));
}

// PolygonLight::pdfAreaAsSolidAngle: the density of area sampling reaching point p of the light from x,
// d² / (area |cos θp|), 0 where it is not a finite positive float.
HWY_INLINE VF pdfPolygonArea(const PolygonLanes& light, const V3F& x, const V3F& p) {
  const DD dd;
  const V3D toPoint = minus(promote(p), promote(x));
  const VD d2 = dot(toPoint, toPoint);
  const VD cosArea = hn::Abs(dot(promote(light.n), toPoint)) * promote(light.area);
  const VD pdf = d2 * hn::Sqrt(d2) / cosArea;
  const MD ok =
      hn::And(toD(light.area > hn::Zero(DF())), hn::And(cosArea > hn::Zero(dd), pdf < setD(double(FLT_MAX))));
  return demote(hn::IfThenElseZero(ok, pdf));
}

// PolygonLight::sampleAlong and the solid-angle technique's density: the sample of unit direction w
// from x towards the light (valid where it meets its plane in front of x and the density fits a float).
HWY_INLINE PacketLightSample sampleAlong(const PolygonLanes& light, const V3D& x, const V3D& w, VD pdf,
                                         MD m) {
  const V3D n = promote(light.n);
  const VD t = dot(n, minus(promote(light.p0), x)) / dot(n, w);
  const MD along = hn::And(m, hn::And(t > hn::Zero(DD()), t < setD(double(FLT_MAX))));
  PacketLightSample s;
  s.wi = demote(w);
  s.dist = demote(t);
  s.pdf = hn::IfThenElseZero(toF(along), floatDensity(pdf));
  s.valid = s.pdf > hn::Zero(DF());
  s.projected = hn::Zero(DF());
  return s;
}

// LightTechnique<kMeasure, PolygonLight> of the polygon light of each lane of `active` (`light`; `index`
// its index among the area lights, per lane) at the lanes' shading points, for draws before drawEnd:
// sample(draws, j) draws the light sample of draw j.
template <LightMeasure kMeasure>
struct PolygonTechnique {
  static constexpr bool kMaps = kMeasure == LightMeasure::SolidAngle;
  static constexpr bool kProjected = kMeasure == LightMeasure::ProjectedSolidAngle;
  struct NoMap {};
  const PolygonLanes& light;
  V3F x, n;
  // By the solid angle: the triangle lights' and the parallelogram lights' maps.
  SphericalTriangleLanes triangle;
  SphericalRectangleLanes rectangle;
  bool anyTriangle = false, anyRectangle = false;
  // By the projected solid angle: the clipped polygon's map.
  std::conditional_t<kProjected, ProjectedPolygonLanes, NoMap> projected;
  bool anyProjected = false;
  MF scalarLanes;  // the lanes the scalar technique samples (set by the constructor)
  ScalarLightSamples<kMeasure> scalar;

  PolygonTechnique(const PacketScene& scene, const PolygonLanes& l, const float* index, const PacketHit& h,
                   MF active, size_t drawEnd)
      : light(l), x(h.p), n(h.ns), scalar(scene, index, h, byScalar(active), drawEnd) {}

  PacketLightSample sample(const PacketDraws& draws, size_t j) const {
    VF u0, u1;
    loadDraw(draws, j, u0, u1);
    if constexpr (kMeasure == LightMeasure::Area) return samplePolygonArea(light, x, u0, u1);
    const VF zero = hn::Zero(DF());
    PacketLightSample s{hn::FirstN(DF(), 0), V3F{zero, zero, zero}, zero, zero, zero};
    const V3D origin = promote(x);
    if constexpr (kProjected) {
      if (anyProjected) {
        // The density of the map's own sample, cos θ / Ω⊥, without its inside test.
        const V3D w = sampleProjectedPolygon(projected, u0, u1);
        s = sampleAlong(light, origin, w, dot(w, projected.ez) / projected.projectedSolidAngle,
                        projected.inLanes);
        s.projected = projected.projected;
      }
      return scalar.merge(draws, j, s);
    }
    if (anyTriangle) {
      const V3D w = sampleSphericalTriangle(triangle, u0, u1);
      s = sampleAlong(light, origin, w, pdfSphericalTriangle(triangle, w), triangle.inLanes);
    }
    if (anyRectangle) {
      const V3D w = sampleSphericalRectangle(rectangle, u0, u1);
      const PacketLightSample r =
          sampleAlong(light, origin, w, pdfSphericalRectangle(rectangle, w), rectangle.inLanes);
      const MF m = toF(rectangle.inLanes);
      s = {hn::Or(s.valid, r.valid), select(m, r.wi, s.wi), hn::IfThenElse(m, r.dist, s.dist),
           hn::IfThenElse(m, r.pdf, s.pdf), s.projected};
    }
    return scalar.merge(draws, j, s);
  }

  // LightTechnique<kMeasure, PolygonLight>::pdf of unit direction w that reached the lanes' light at p
  // (its normal nLight): in lanes, and the scalar technique's in the lanes it samples.
  VF pdf(const V3F& w, const V3F& p, const V3F& nLight) const {
    return scalar.mergePdf(w, p, nLight, lanesPdf(w, p));
  }
  // The same density outside scalarLanes.
  VF lanesPdf(const V3F& w, const V3F& p) const {
    if constexpr (kMeasure == LightMeasure::Area) {
      return pdfPolygonArea(light, x, p);
    } else {
      VD d = hn::Zero(DD());
      const V3D wD = promote(w);
      if constexpr (kProjected) {
        if (anyProjected) d = pdfProjectedPolygon(projected, wD);
      } else {
        if (anyTriangle) d = pdfSphericalTriangle(triangle, wD);
        if (anyRectangle) d = hn::IfThenElse(rectangle.inLanes, pdfSphericalRectangle(rectangle, wD), d);
      }
      return floatDensity(d);
    }
  }

 private:
  // scalarLanes, found by setting up the maps of the other lanes of `active`.
  MF byScalar(MF active) {
    scalarLanes = lanesByScalar(active);
    return scalarLanes;
  }
  MF lanesByScalar(MF active) {
    if constexpr (kProjected) {
      if (hn::AllFalse(DF(), active)) return active;
      projectedPolygon(light, x, n, active, projected);
      anyProjected = !hn::AllFalse(DD(), projected.inLanes);
      return hn::FirstN(DF(), 0);  // every polygon is mapped in lanes, clipped to the horizon or not
    }
    if constexpr (!kMaps) return hn::FirstN(DF(), 0);
    const MF triangles = hn::AndNot(light.parallelogram, active);
    const MF parallelograms = hn::And(light.parallelogram, active);
    MF scalarLanes = hn::FirstN(DF(), 0);
    if (!hn::AllFalse(DF(), triangles)) {
      triangle = sphericalTriangle(light, x, triangles);
      anyTriangle = !hn::AllFalse(DD(), triangle.inLanes);
      scalarLanes = toF(triangle.byArea);
    }
    if (!hn::AllFalse(DF(), parallelograms)) {
      rectangle = sphericalRectangle(light, x, parallelograms);
      anyRectangle = !hn::AllFalse(DD(), rectangle.inLanes);
      scalarLanes = hn::Or(scalarLanes, toF(rectangle.scalar));
    }
    return scalarLanes;
  }
};

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
