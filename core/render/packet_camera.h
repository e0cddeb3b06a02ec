// The camera and pixel filter of a packet row loop as plain values for the lanes (packet_camera-inl.h):
// PerspectiveCamera::generateRay's basis and constants and FilterSampler's tables.
#pragma once

#include "core/render/camera.h"
#include "core/render/filter.h"

namespace penumbra {

struct PacketCamera {
  float origin[3], right[3], up[3], forward[3];
  float tanHalfX, tanHalfY, invWidth, invHeight, nearClip, farClip;
  FilterSampler::Tables filter;  // points into the FilterSampler it was made from
};

// `filter` must outlive the result.
PacketCamera makePacketCamera(const PerspectiveCamera& camera, const FilterSampler& filter);

}  // namespace penumbra
