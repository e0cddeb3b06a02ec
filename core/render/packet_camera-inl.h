// Camera rays in lanes: FilterSampler::sample's offset from each lane's pixel centre and
// PerspectiveCamera::generateRay through it, mirrored operation by operation in float.
// Part of the packet kernels: included by packet_kernels.cpp once per instruction set (Highway's
// re-inclusion toggle below), inside that set's namespace.
#if defined(PENUMBRA_PACKET_CAMERA_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef PENUMBRA_PACKET_CAMERA_INL_H_
#undef PENUMBRA_PACKET_CAMERA_INL_H_
#else
#define PENUMBRA_PACKET_CAMERA_INL_H_
#endif

#include <hwy/highway.h>

#include "core/render/packet_camera.h"
#include "core/render/packet_kernels.h"
#include "core/render/packet_math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace penumbra {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using VI = hn::Vec<DI>;

// FilterSampler::sample1D: the inverse CDF's table interpolated at u, the signed filter's bin weight.
HWY_INLINE VF filterOffset1D(const FilterSampler::Tables& f, VF u, VF& weight) {
  const DF df;
  const DI di;
  const VF t = u * setF(float(FilterSampler::kTable));
  const VI k = hn::Min(hn::ConvertTo(di, t), hn::Set(di, FilterSampler::kTable - 1));
  const VF lo = hn::GatherIndex(df, f.invCdf, k);
  const VF hi = hn::GatherIndex(df, f.invCdf + 1, k);
  const VF x = lo + (t - hn::ConvertTo(df, k)) * (hi - lo);
  weight = setF(1.f);
  if (f.isSigned) {
    VI bin = hn::ConvertTo(di, (x + setF(f.radius)) * setF(f.invBinWidth));
    bin = hn::Min(hn::Max(bin, hn::Zero(di)), hn::Set(di, FilterSampler::kBins - 1));
    weight = hn::GatherIndex(df, f.binWeight, bin);
  }
  return x;
}

// startCameraSample after the filter's draw, for pixels x0 .. x0 + count - 1 of row y (lanes past
// `count` repeat the last): each lane's ray through its filtered image position, and the filter's
// weight.
HWY_INLINE void cameraRays(const PacketCamera& c, int x0, int y, int count,
                           const float (&u)[2][kMaxPacketLanes], PacketRays& rays,
                           float (&weight)[kMaxPacketLanes]) {
  const DF df;
  const DI di;
  VF wx, wy;
  const VF offsetX = filterOffset1D(c.filter, hn::LoadU(df, u[0]), wx);
  const VF offsetY = filterOffset1D(c.filter, hn::LoadU(df, u[1]), wy);
  hn::StoreU(wx * wy, df, weight);
  const VI pixel = hn::Min(hn::Iota(di, 0), hn::Set(di, count - 1)) + hn::Set(di, x0);
  const VF half = setF(0.5f), one = setF(1.f), two = setF(2.f);
  const VF px = hn::ConvertTo(df, pixel) + half + offsetX;
  const VF py = setF(float(y)) + half + offsetY;
  // generateRay.
  const VF sx = px * setF(c.invWidth), sy = py * setF(c.invHeight);
  const VF x = (one - two * sx) * setF(c.tanHalfX), yy = (one - two * sy) * setF(c.tanHalfY);
  const VF len = hn::Sqrt(x * x + yy * yy + one);
  const VF inv = one / len;
  for (int i = 0; i < 3; ++i) {
    const VF d = (setF(c.right[i]) * x + setF(c.up[i]) * yy + setF(c.forward[i])) * inv;
    hn::StoreU(d, df, rays.d[i]);
    hn::StoreU(setF(c.origin[i]), df, rays.o[i]);
  }
  hn::StoreU(setF(c.nearClip) * len, df, rays.tMin);
  hn::StoreU(setF(c.farClip) * len, df, rays.tMax);
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra
HWY_AFTER_NAMESPACE();

#endif
