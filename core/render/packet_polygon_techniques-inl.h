// The light-sampling techniques of polygon lights in the packet kernels (LightTechnique<measure,
// PolygonLight> in lanes), of one light broadcast to every lane or of each lane's own: by area in lanes
// (samplePolygonArea); by the solid angle and the projected solid angle by the scalar techniques lane by
// lane (ScalarLightSamples), the rest of each draw (shadow ray, reflection, weights, sums) in lanes.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_POLYGON_TECHNIQUES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_POLYGON_TECHNIQUES_INL_H_
#undef PENUMBRA_PACKET_POLYGON_TECHNIQUES_INL_H_
#else
#define PENUMBRA_PACKET_POLYGON_TECHNIQUES_INL_H_
#endif

#include <hwy/highway.h>

#include "core/render/packet_bsdf-inl.h"
#include "core/render/packet_geometry-inl.h"
#include "core/render/packet_lights-inl.h"
#include "core/render/packet_math-inl.h"
#include "core/render/packet_scalar_samples-inl.h"
#include "core/render/packet_scene.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// LightTechnique<kMeasure, PolygonLight> of the polygon light of each lane of `active` (`light`; `index`
// its index among the area lights, per lane) at the lanes' shading points, for draws before drawEnd:
// sample(draws, j) draws the light sample of draw j.
template <LightMeasure kMeasure>
struct PolygonTechnique {
  const PolygonLanes& light;
  V3F x;
  ScalarLightSamples<kMeasure> scalar;

  PolygonTechnique(const PacketScene& scene, const PolygonLanes& l, const float* index, const PacketHit& h,
                   MF active, size_t drawEnd)
      : light(l),
        x(h.p),
        scalar(scene, index, h, kMeasure == LightMeasure::Area ? hn::FirstN(DF(), 0) : active, drawEnd) {}

  PacketLightSample sample(const PacketDraws& draws, size_t j) const {
    if constexpr (kMeasure == LightMeasure::Area) {
      VF u0, u1;
      loadDraw(draws, j, u0, u1);
      return samplePolygonArea(light, x, u0, u1);
    } else {
      const VF zero = hn::Zero(DF());
      return scalar.merge(draws, j,
                          PacketLightSample{hn::FirstN(DF(), 0), V3F{zero, zero, zero}, zero, zero, zero});
    }
  }
};

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
