// The row loop of the packet path: camera samples W at a time (W = packetLanes()). Per packet, each
// lane's sample stream is restarted and drawn in the scalar loop's order (the filter offset, then
// every light's draws), the camera rays and draws go to the packet kernel in structure-of-arrays
// form, and each lane's radiance is accumulated as the scalar loop does. The image equals the scalar
// row loop's (row_loop.h) bit for bit on every instruction set.
#pragma once

#include "core/render/row_renderer.h"

namespace penumbra {

// Whether the packet path is on, from the environment variable PENUMBRA_SIMD, read once: unset or
// "auto", the best instruction set this CPU has; "off", one camera sample at a time everywhere; an
// instruction set by Highway's name (AVX3 = AVX-512, AVX2, SSE4, EMU128 = portable), that one. An
// unknown name is reported on stderr and ignored.
bool packetPathEnabled();

// For a job that packetUnsupportedReason(job) accepts; the preview is `scalar`'s.
RowRenderer packetRowsFor(const RenderJob& job, RowRenderer scalar);

}  // namespace penumbra
