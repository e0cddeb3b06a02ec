// The light samples the packet kernels leave to the scalar techniques, lane by lane: each lane's area
// light sampled by LightTechnique<measure, Light> itself (queryLightSamples), for the lanes whose map
// the kernels do not compute in lanes, merged into a packet's sample.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_SCALAR_SAMPLES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_SCALAR_SAMPLES_INL_H_
#undef PENUMBRA_PACKET_SCALAR_SAMPLES_INL_H_
#else
#define PENUMBRA_PACKET_SCALAR_SAMPLES_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <array>

#include "core/render/packet_geometry-inl.h"
#include "core/render/packet_lights-inl.h"
#include "core/render/packet_math-inl.h"
#include "core/render/packet_queries.h"
#include "core/render/packet_scene.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Area light `light`'s index in every lane.
HWY_INLINE std::array<float, kMaxPacketLanes> broadcastIndex(size_t light) {
  std::array<float, kMaxPacketLanes> index;
  index.fill(float(light));
  return index;
}

// The scalar technique's samples of each lane's area light (index among the area lights, per lane) at
// the shading points of the lanes `lanes`, for draws before drawEnd. Queried kChunk draws at a time, so
// that each lane's technique (whose set-up is the costly part) is set up once per chunk, not per draw.
template <LightMeasure kMeasure>
class ScalarLightSamples {
 public:
  static constexpr size_t kChunk = 8;

  ScalarLightSamples(const PacketScene& scene, const float* light, const PacketHit& h, MF lanes,
                     size_t drawEnd)
      : scene_(scene), lanes_(lanes), drawEnd_(drawEnd), any_(!hn::AllFalse(DF(), lanes)) {
    if (!any_) return;
    std::copy(light, light + hn::Lanes(DF()), light_);
    storeShading(h, lanes, points_);
  }

  // s with the scalar sample of draw j (j < drawEnd) in the lanes of `lanes`.
  PacketLightSample merge(const PacketDraws& draws, size_t j, PacketLightSample s) const {
    if (!any_) return s;
    if (j < first_ || j >= first_ + count_) {
      first_ = j;
      count_ = std::min(kChunk, drawEnd_ - j);
      queryLightSamples(*scene_.scene, kMeasure, light_, points_, draws, first_, int(count_),
                        int(hn::Lanes(DF())), chunk_);
    }
    const DF df;
    const PacketLightSampleLanes& q = chunk_[j - first_];
    const MF m = lanes_;
    s.wi = select(m, loadF3(q.wi), s.wi);
    s.dist = hn::IfThenElse(m, hn::LoadU(df, q.dist), s.dist);
    s.pdf = hn::IfThenElse(m, hn::LoadU(df, q.pdf), s.pdf);
    s.projected = hn::IfThenElse(m, hn::LoadU(df, q.projected), s.projected);
    s.valid = hn::Or(hn::AndNot(m, s.valid), hn::And(m, s.pdf > hn::Zero(df)));
    return s;
  }

  // d with MisIntegrator::lightPdf of unit direction w, which reached the lanes' light at p with normal
  // n, in the lanes of `lanes`.
  VF mergePdf(const V3F& w, const V3F& p, const V3F& n, VF d) const {
    if (!any_) return d;
    const DF df;
    HWY_ALIGN float pdf[kMaxPacketLanes];
    PacketColorLanes wl, pl, nl;
    storeF3(w, wl.c);
    storeF3(p, pl.c);
    storeF3(n, nl.c);
    queryLightPdfs(*scene_.scene, kMeasure, points_, light_, wl.c, pl.c, nl.c, int(hn::Lanes(df)), pdf);
    return hn::IfThenElse(lanes_, hn::Load(df, pdf), d);
  }

 private:
  const PacketScene& scene_;
  MF lanes_;
  size_t drawEnd_;
  bool any_;
  HWY_ALIGN float light_[kMaxPacketLanes];
  PacketShadingLanes points_;
  mutable size_t first_ = 0, count_ = 0;
  mutable PacketLightSampleLanes chunk_[kChunk];
};

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
