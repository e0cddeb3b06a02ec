// The packet kernels: the radiance of W camera rays at once, structure of arrays, one lane per camera
// sample (W = the double lanes of the widest instruction set the CPU has: 8 on AVX-512, 4 on AVX2, 2 on
// SSE4 and the portable fallback; the scalar code they mirror computes in double where it needs to, so
// lanes are as wide as a double vector). Compiled once per instruction set by Highway
// (packet_kernels.cpp) and chosen at run time. Each kernel computes, lane by lane, exactly what the
// scalar integrator computes for that ray (same operations in the same order, no fused multiply-add),
// so the images are the same bit for bit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/render/packet_camera.h"
#include "core/render/packet_scene.h"
#include "core/sampling/sobol_stream.h"

namespace penumbra {

inline constexpr int kMaxPacketLanes = 8;

// Camera rays of one packet. Lanes beyond the packet's pixels repeat a valid ray (their results are
// not used).
struct alignas(64) PacketRays {
  float o[3][kMaxPacketLanes];
  float d[3][kMaxPacketLanes];
  float tMin[kMaxPacketLanes];
  float tMax[kMaxPacketLanes];
};

// The sampler's draws of each lane's shading samples (PacketScene::drawCount of them), in the order
// the scalar integrator draws them: draw j in u[j][0] and u[j][1]. For light sampling, draw j is
// light j / samples, sample j % samples.
struct alignas(64) PacketDraws {
  float u[kMaxPacketDraws][2][kMaxPacketLanes];
};

struct alignas(64) PacketRadiance {
  float L[3][kMaxPacketLanes];
};

// Lanes per packet of the instruction set in use.
int packetLanes();
// The instruction set in use ("AVX3" is AVX-512), as Highway names it.
std::string packetTargetName();
// The instruction sets this binary has kernels for that this CPU runs, best first (Highway's names).
std::vector<std::string> availablePacketTargets();
// Restricts the kernels to the instruction set `name` (one of availablePacketTargets()), or lifts the
// restriction for "" or "auto". False if `name` is not available. Not thread-safe: call before
// rendering (tests, benchmarks, PENUMBRA_SIMD).
bool forcePacketTarget(const std::string& name);

// The radiance of each lane's camera ray by the scene's kernel.
using PacketShader = void (*)(const PacketScene& scene, const PacketRays& rays, const PacketDraws& draws,
                              PacketRadiance& out);
// Each lane's camera ray and filter weight (startCameraSample after its filter draw u[.][lane], in
// lanes) for pixels x0 .. x0 + count - 1 of row y; lanes past `count` repeat the last pixel.
using PacketCameraRays = void (*)(const PacketCamera& camera, int x0, int y, int count,
                                  const float (&u)[2][kMaxPacketLanes], PacketRays& rays,
                                  float (&weight)[kMaxPacketLanes]);
// Each lane's filter draw (u) and first `drawCount` shading draws of SamplerKind::Independent for pixels
// x0 .. x0 + count - 1 of row y at sample index `pass` (lanes past `count` repeat the last pixel): what
// Sampler::startPixelSample and the row loop's next2D calls return, computed in lanes. `seedHash` is
// mix64 of the sampler's seed.
using PacketIndependentDraws = void (*)(uint64_t seedHash, int x0, int y, int count, uint32_t pass,
                                        int drawCount, float (&u)[2][kMaxPacketLanes], PacketDraws& draws);
// Each lane's start of its pixel sample's `sobol` or `zsobol` stream (BasicSobolStream's start).
struct alignas(64) PacketSobolStart {
  uint64_t key[kMaxPacketLanes];  // hash of (seed, pixel); zsobol: of (seed, the tile's Morton code)
  uint32_t reversedTileCode[kMaxPacketLanes];  // zsobol: the pixel's Morton code in its tile, bit-reversed
  bool zsobol;
  uint32_t log2Samples;  // zsobol: zsobolLog2Samples of the run's sample count
  uint32_t pass;         // the sample index
};

// Each lane's filter draw (draws[0], into u) and shading draws (draws[1..], into out.u[0..]) of the
// Sobol' samplers, `requests` being sobolRequests(draws): what Sampler::next2D's forms return after
// the lanes' starts, computed in lanes.
using PacketSobolDraws = void (*)(const PacketSobolStart& start, const SobolDrawCall* draws,
                                  const uint32_t* requests, int drawCount, float (&u)[2][kMaxPacketLanes],
                                  PacketDraws& out);

// The kernels of one instruction set.
struct PacketKernels {
  PacketShader shade;
  PacketCameraRays cameraRays;
  PacketIndependentDraws independentDraws;
  PacketSobolDraws sobolDraws;
};
// The kernels of the instruction set in use when it is called (a row renderer takes them once, not
// per packet).
const PacketKernels& packetKernels();

}  // namespace penumbra
