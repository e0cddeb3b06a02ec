// The packet kernels: the radiance of W camera rays at once, structure of arrays, one lane per camera
// sample (W = the double lanes of the widest instruction set the CPU has: 8 on AVX-512, 4 on AVX2, 2 on
// SSE4 and the portable fallback; the scalar code they mirror computes in double where it needs to, so
// lanes are as wide as a double vector). Compiled once per instruction set by Highway
// (packet_kernels.cpp) and chosen at run time. Each kernel computes, lane by lane, exactly what the
// scalar integrator computes for that ray (same operations in the same order, no fused multiply-add),
// so the images are the same bit for bit.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry/ray.h"
#include "core/render/packet_camera.h"
#include "core/render/packet_scene.h"
#include "core/sampling/sampler.h"
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

// Lane k's camera ray.
inline Ray cameraRay(const PacketRays& rays, int k) {
  Ray ray;
  ray.o = Vec3(rays.o[0][k], rays.o[1][k], rays.o[2][k]);
  ray.d = Vec3(rays.d[0][k], rays.d[1][k], rays.d[2][k]);
  ray.tMin = rays.tMin[k];
  ray.tMax = rays.tMax[k];
  return ray;
}

// One draw of every lane: lane k's two floats in u[0][k] and u[1][k].
struct alignas(64) PacketDraw {
  float u[2][kMaxPacketLanes];
};

// The sampler's draws of each lane's shading samples, in the order the scalar integrator draws them:
// draw j in draw[j]. For light sampling, draw j is light j / samples, sample j % samples. A view of
// storage sized to the render's draws (one buffer per worker, PacketDrawBuffer).
struct PacketDraws {
  PacketDraw* draw = nullptr;
};

// Room for `count` draws of every lane (at least one), owned by one worker and reused packet after
// packet. Not copyable, so a view taken of it never points into a copy's storage (a move keeps it).
class PacketDrawBuffer {
 public:
  explicit PacketDrawBuffer(size_t count) : storage_(std::max<size_t>(count, 1)) {}
  PacketDrawBuffer(const PacketDrawBuffer&) = delete;
  PacketDrawBuffer& operator=(const PacketDrawBuffer&) = delete;
  PacketDrawBuffer(PacketDrawBuffer&&) noexcept = default;
  PacketDrawBuffer& operator=(PacketDrawBuffer&&) noexcept = default;
  PacketDraws draws() { return {storage_.data()}; }

 private:
  std::vector<PacketDraw> storage_;
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

struct PacketHitLanes;
// The radiance of each lane's camera ray by the scene's kernel. Where the scene's rays are queried
// (PacketScene::geometryQueried), `queried` holds the rays' hits (queryCameraHits); elsewhere it is
// not read and the kernel finds the hits in lanes.
using PacketShader = void (*)(const PacketScene& scene, const PacketRays& rays, const PacketHitLanes* queried,
                              const PacketDraws& draws, PacketRadiance& out);
// Each lane's camera ray and filter weight (startCameraSample after its filter draw u[.][lane], in
// lanes) for pixels x0 .. x0 + count - 1 of row y; lanes past `count` repeat the last pixel.
using PacketCameraRays = void (*)(const PacketCamera& camera, int x0, int y, int count,
                                  const float (&u)[2][kMaxPacketLanes], PacketRays& rays,
                                  float (&weight)[kMaxPacketLanes]);
// Each lane's start of its pixel sample's stream (Sampler::startPixelSample): the word its key combines
// with the seed's hash, and the run's settings its sampler kind reads.
struct alignas(64) PacketStreamStart {
  uint64_t seedHash;                           // Sampler::seedHash
  uint64_t word[kMaxPacketLanes];              // pixelStreamWord; zsobol: zsobolTileWord
  uint32_t reversedTileCode[kMaxPacketLanes];  // zsobol: zsobolReversedTileCode
  SamplerKind kind;
  uint32_t pass;         // the sample index
  uint32_t gridSide;     // stratified: Sampler::gridSide
  uint32_t log2Samples;  // zsobol: Sampler::zsobolLog2Samples
};

// A camera sample's sampler calls in the integrator's order: the filter's next2D() first, then the
// scene's draw requests unrolled, one call each; and the request each takes in the Sobol' streams
// (sobolRequests of the calls).
struct PacketDrawPlan {
  const SobolDrawCall* calls;
  const uint32_t* requests;
  int count;
};

// Each lane's filter draw (the plan's first call, into u) and shading draws (the others, into
// draws.draw[0..]): what Sampler::next2D's forms return after Sampler::startPixelSample, for every
// sampler kind, computed in lanes.
using PacketSamplerDraws = void (*)(const PacketStreamStart& start, const PacketDrawPlan& plan,
                                    float (&u)[2][kMaxPacketLanes], PacketDraws& draws);

// Film::add of each of the first `count` lanes' radiance times its filter weight, to the pixel sums
// from `sums` on (6 doubles per pixel, Film::sumsAt), skipping lanes whose radiance fails
// isValidRadiance; returns how many did.
using PacketFilmAdd = uint32_t (*)(const PacketRadiance& radiance, const float (&weight)[kMaxPacketLanes],
                                   int count, double* sums);

// UniformLightSelection::pick or PowerLightSelection::pick (as `table`) of each lane whose active[k] is
// not 0, from its pick draw (u[0][k] + u[1][k] 2^-24): light[k] the light's index (-1 where nothing is
// picked, and in inactive lanes) and pmf[k] its probability (0 there). The shading kernels pick this way;
// this entry lets the pick be tested alone.
using PacketTablePicks = void (*)(const PacketLightTable& table, const float (&u)[2][kMaxPacketLanes],
                                  const float (&active)[kMaxPacketLanes], float (&light)[kMaxPacketLanes],
                                  double (&pmf)[kMaxPacketLanes]);

// LightTechnique<ProjectedSolidAngle, PolygonLight>'s map of lane k's polygon light (polygons[k]) seen
// from x[.][k] with shading normal n[.][k], in the lanes whose active[k] is not 0: mapped[k] is 1 where
// the lanes sample it (then w[.][k] is the direction of draw u and projected[k] its Ω⊥), 0 where nothing
// is sampled. The shading kernels sample this way; this entry lets the map be tested alone.
using PacketProjectedPolygons =
    void (*)(const std::vector<PacketPolygonLight>& polygons, const float (&x)[3][kMaxPacketLanes],
             const float (&n)[3][kMaxPacketLanes], const float (&active)[kMaxPacketLanes],
             const float (&u)[2][kMaxPacketLanes], double (&w)[3][kMaxPacketLanes],
             double (&projected)[kMaxPacketLanes], float (&mapped)[kMaxPacketLanes]);

// LightTechnique<measure, PolygonLight>::pdf of unit direction w[.][k], which reaches lane k's polygon
// light (polygons[k]) at p[.][k], seen from x[.][k] with shading normal n[.][k], in the lanes whose
// active[k] is not 0, as the lanes compute it: byScalar[k] is 1 (and pdf[k] 0) where the scalar
// technique computes it instead. MIS's shading kernels weight this way; this entry lets the densities
// be tested alone.
using PacketPolygonLightPdfs = void (*)(LightMeasure measure, const std::vector<PacketPolygonLight>& polygons,
                                        const float (&x)[3][kMaxPacketLanes],
                                        const float (&n)[3][kMaxPacketLanes],
                                        const float (&active)[kMaxPacketLanes],
                                        const float (&w)[3][kMaxPacketLanes],
                                        const float (&p)[3][kMaxPacketLanes], float (&pdf)[kMaxPacketLanes],
                                        float (&byScalar)[kMaxPacketLanes]);

// ProjectedPolygon::azimuthIntervals as the projected polygon's lanes compute it, for lane k's vertex
// pseudo-angles alpha[.][k] (count[k] of them, 3 to 5): intervals[s][.][k] is interval s's from, to,
// edgeA and edgeB, or -1 each where the s-th and (s+1)-th azimuths in order are equal (the non-empty
// ones, in order, are the scalar function's). This entry lets the intervals be tested alone.
using PacketAzimuthIntervals = void (*)(const double (&alpha)[5][kMaxPacketLanes],
                                        const double (&count)[kMaxPacketLanes],
                                        double (&intervals)[4][4][kMaxPacketLanes]);

// The kernels of one instruction set.
struct PacketKernels {
  PacketShader shade;
  PacketCameraRays cameraRays;
  PacketSamplerDraws samplerDraws;
  PacketFilmAdd filmAdd;
  PacketTablePicks tablePicks;
  PacketProjectedPolygons projectedPolygons;
  PacketPolygonLightPdfs polygonLightPdfs;
  PacketAzimuthIntervals azimuthIntervals;
};
// The kernels of the instruction set in use when it is called (a row renderer takes them once, not
// per packet).
const PacketKernels& packetKernels();

}  // namespace penumbra
