// The packet kernels' test entries (PacketKernels' tablePicks, projectedPolygons, polygonLightPdfs and
// azimuthIntervals): one piece of a kernel run alone on arrays, so that tests can compare it with the
// scalar code it mirrors. The renderer never calls them.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), after the kernels.
#if defined(PENUMBRA_PACKET_TEST_ENTRIES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_TEST_ENTRIES_INL_H_
#undef PENUMBRA_PACKET_TEST_ENTRIES_INL_H_
#else
#define PENUMBRA_PACKET_TEST_ENTRIES_INL_H_
#endif

#include <hwy/highway.h>

#include <vector>

#include "core/render/packet_geometry-inl.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_light_table-inl.h"
#include "core/render/packet_lights-inl.h"
#include "core/render/packet_math-inl.h"
#include "core/render/packet_polygon_techniques-inl.h"
#include "core/render/packet_projected_polygon-inl.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// 0, 1, 2, ... in each lane: lane k takes entry k of the test's arrays.
struct LaneIndices {
  HWY_ALIGN float k[kMaxPacketLanes];
  LaneIndices() {
    for (int i = 0; i < kMaxPacketLanes; ++i) k[i] = float(i);
  }
};

void TablePicks(const PacketLightTable& table, const float (&u)[2][kMaxPacketLanes],
                const float (&active)[kMaxPacketLanes], float (&light)[kMaxPacketLanes],
                double (&pmf)[kMaxPacketLanes]) {
  const DF df;
  pickTableLights(table, hn::LoadU(df, u[0]), hn::LoadU(df, u[1]), hn::LoadU(df, active) != hn::Zero(df),
                  light, pmf);
}
void ProjectedPolygons(const std::vector<PacketPolygonLight>& polygons, const float (&x)[3][kMaxPacketLanes],
                       const float (&n)[3][kMaxPacketLanes], const float (&active)[kMaxPacketLanes],
                       const float (&u)[2][kMaxPacketLanes], double (&w)[3][kMaxPacketLanes],
                       double (&projected)[kMaxPacketLanes], float (&mapped)[kMaxPacketLanes]) {
  const DF df;
  const DD dd;
  const LaneIndices index;
  const PolygonLanes light = gatherPolygons(polygons, index.k);
  ProjectedPolygonLanes map;
  projectedPolygon(light, loadF3(x), loadF3(n), hn::LoadU(df, active) != hn::Zero(df), map);
  const VD zero = hn::Zero(dd);
  const V3D dir = hn::AllFalse(dd, map.inLanes)
                      ? V3D{zero, zero, zero}
                      : sampleProjectedPolygon(map, hn::LoadU(df, u[0]), hn::LoadU(df, u[1]));
  hn::StoreU(dir.x, dd, w[0]);
  hn::StoreU(dir.y, dd, w[1]);
  hn::StoreU(dir.z, dd, w[2]);
  hn::StoreU(hn::IfThenElseZero(map.inLanes, map.projectedSolidAngle), dd, projected);
  hn::StoreU(hn::IfThenElseZero(toF(map.inLanes), setF(1.f)), df, mapped);
}
template <LightMeasure kMeasure>
void polygonLightPdfs(const std::vector<PacketPolygonLight>& polygons, const V3F& x, const V3F& n, MF active,
                      const V3F& w, const V3F& p, float (&pdf)[kMaxPacketLanes],
                      float (&byScalar)[kMaxPacketLanes]) {
  const DF df;
  const LaneIndices index;
  PacketScene scene;  // the scalar lanes are reported, not computed: no scene to query
  scene.polygons = polygons;
  PacketHit h{};
  h.p = x;
  h.ns = n;
  const PolygonLanes light = gatherPolygons(polygons, index.k);
  const PolygonTechnique<kMeasure> technique(scene, light, index.k, h, active, 0);
  hn::StoreU(hn::IfThenZeroElse(technique.scalarLanes, technique.lanesPdf(w, p)), df, pdf);
  hn::StoreU(hn::IfThenElseZero(technique.scalarLanes, setF(1.f)), df, byScalar);
}
void PolygonLightPdfs(LightMeasure measure, const std::vector<PacketPolygonLight>& polygons,
                      const float (&x)[3][kMaxPacketLanes], const float (&n)[3][kMaxPacketLanes],
                      const float (&active)[kMaxPacketLanes], const float (&w)[3][kMaxPacketLanes],
                      const float (&p)[3][kMaxPacketLanes], float (&pdf)[kMaxPacketLanes],
                      float (&byScalar)[kMaxPacketLanes]) {
  const DF df;
  const MF on = hn::LoadU(df, active) != hn::Zero(df);
  const V3F xs = loadF3(x), ns = loadF3(n), ws = loadF3(w), ps = loadF3(p);
  switch (measure) {
    case LightMeasure::Area:
      return polygonLightPdfs<LightMeasure::Area>(polygons, xs, ns, on, ws, ps, pdf, byScalar);
    case LightMeasure::SolidAngle:
      return polygonLightPdfs<LightMeasure::SolidAngle>(polygons, xs, ns, on, ws, ps, pdf, byScalar);
    case LightMeasure::ProjectedSolidAngle:
      return polygonLightPdfs<LightMeasure::ProjectedSolidAngle>(polygons, xs, ns, on, ws, ps, pdf, byScalar);
  }
}
void AzimuthIntervals(const double (&alpha)[5][kMaxPacketLanes], const double (&count)[kMaxPacketLanes],
                      double (&intervals)[4][4][kMaxPacketLanes]) {
  const DD dd;
  VD alphas[5];
  for (int i = 0; i < 5; ++i) alphas[i] = hn::LoadU(dd, alpha[i]);
  projected_polygon::IntervalLanes found[ProjectedPolygonLanes::kIntervals];
  projected_polygon::azimuthIntervals(alphas, hn::LoadU(dd, count), found);
  for (int s = 0; s < 4; ++s) {
    hn::StoreU(found[s].from, dd, intervals[s][0]);
    hn::StoreU(found[s].to, dd, intervals[s][1]);
    hn::StoreU(found[s].edgeA, dd, intervals[s][2]);
    hn::StoreU(found[s].edgeB, dd, intervals[s][3]);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
