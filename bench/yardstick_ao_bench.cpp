// The AO yardstick, measured in the same run as the renderer: bare loops of Embree calls on the
// stand-in AO scene (scenes/standin/rock-ao.xml: 1,310,720 triangles of a procedural rock on a
// ground plane, 768 x 576, 4 cosine AO rays per camera sample) against penumbra's general renderer.
// Items are AO rays (4 per camera sample), so the ratio of items/s is the renderer's share of what
// the traversal alone allows. One thread each: the question is the work per ray, not scaling.
//   build/penumbra_bench --benchmark_filter=RockAo --benchmark_repetitions=5
//     --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
//
// Every loop builds the same Embree scene as the renderer (the meshes as loaded, RTC_BUILD_QUALITY_HIGH,
// RTC_SCENE_FLAG_ROBUST), traces one jittered camera ray per pixel with rtcIntersect1 (the last: as a
// stream), offsets the hit along its geometric normal and traces 4 cosine-distributed occlusion rays
// from it. They differ only in how the rays are handed to Embree:
//   Occluded1   one rtcOccluded1 per ray
//   Occluded4   the 4 rays of one shading point as an rtcOccluded4 packet
//   Occluded8   the 8 rays of two camera samples as an rtcOccluded8 packet
//   Occluded16  the 16 rays of four camera samples as an rtcOccluded16 packet (CPUs with AVX-512 only)
//   Stream      a row's rays (4 x 768) as one rtcOccluded1M stream (RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT)
//   Streams     Stream, and the row's camera rays as one rtcIntersect1M stream (..._FLAG_COHERENT)
// What the loops leave out and the renderer does: the sampler's draws (Owen-scrambled or PCG), the
// gaussian filter, shading normals, scale-aware ray offsets, per-pixel variance, any scene.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bench/fast_rng.h"
#include "core/geometry/embree_rays.h"
#include "core/math/frame.h"
#include "core/render/camera.h"
#include "core/render/engine.h"
#include "core/render/row_renderer.h"
#include "core/sampling/warp.h"
#include "core/scene/scene_builder.h"

namespace penumbra {
namespace {

const LoadedScene& rockScene() {
  static const LoadedScene scene = loadScene(PENUMBRA_SOURCE_DIR "/scenes/standin/rock-ao.xml");
  return scene;
}

// The renderer's Embree scene, built the same way from the loaded meshes.
struct EmbreeRock {
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(device);
  float rayLength = 0;

  EmbreeRock() {
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    for (const TriangleMesh& mesh : rockScene().scene->geometry.meshes()) {
      RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<Vec3*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           sizeof(Vec3), mesh.positions.size()));
      auto* t = static_cast<glm::uvec3*>(rtcSetNewGeometryBuffer(
          geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(glm::uvec3), mesh.triangles.size()));
      std::copy(mesh.positions.begin(), mesh.positions.end(), v);
      std::copy(mesh.triangles.begin(), mesh.triangles.end(), t);
      rtcCommitGeometry(geom);
      rtcAttachGeometry(scene, geom);
      rtcReleaseGeometry(geom);
    }
    rtcCommitScene(scene);
    rayLength = rockScene().scene->rayLengthBound;
  }
  ~EmbreeRock() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
};

const EmbreeRock& embreeRock() {
  static const EmbreeRock rock;
  return rock;
}

// A shading point: where the camera ray hit, and the frame of its geometric normal (facing the ray).
struct Hit {
  Vec3 p;
  Frame frame;
  bool valid = false;
};

Ray jitteredCameraRay(const PerspectiveCamera& camera, int x, int y, FastRng& rng) {
  return camera.generateRay(Vec2(float(x) + rng.next(), float(y) + rng.next()));
}

Hit shadingPoint(const Ray& ray, const RTCRayHit& rh) {
  Hit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  Vec3 n = glm::normalize(Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
  if (glm::dot(n, ray.d) > 0.f) n = -n;
  hit.p = ray.o + rh.ray.tfar * ray.d + 1e-4f * n;
  hit.frame = Frame(n);
  hit.valid = true;
  return hit;
}

Hit traceCameraRay(const EmbreeRock& rock, const PerspectiveCamera& camera, int x, int y, FastRng& rng) {
  const Ray ray = jitteredCameraRay(camera, x, y, rng);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  setupRayHit(ray, ray.tMax, rh);
  rtcIntersect1(rock.scene, &context, &rh);
  return shadingPoint(ray, rh);
}

// Occlusion ray `k` of a shading point, in lane `lane` of a packet of N rays (SoA layout).
template <class Packet>
void setLane(Packet& r, int lane, const Vec3& o, const Vec3& d, float tfar) {
  r.org_x[lane] = o.x, r.org_y[lane] = o.y, r.org_z[lane] = o.z;
  r.dir_x[lane] = d.x, r.dir_y[lane] = d.y, r.dir_z[lane] = d.z;
  r.tnear[lane] = 0.f, r.tfar[lane] = tfar, r.time[lane] = 0.f;
  r.mask[lane] = ~0u, r.id[lane] = 0, r.flags[lane] = 0;
}

Vec3 cosineDirection(const Frame& frame, FastRng& rng) {
  const float u = rng.next(), v = rng.next();
  return frame.toWorld(Warp::squareToCosineHemisphere(Vec2(u, v)));
}

constexpr int kAoRays = 4;

// Packets of N rays = N / 4 camera samples; lanes of a camera ray that missed are masked off.
template <int N, class Packet, class Occluded>
float pixelsByPackets(const EmbreeRock& rock, const PerspectiveCamera& camera, int y, FastRng& rng,
                      Occluded occluded) {
  constexpr int kSamplesPerPacket = N / kAoRays;
  float total = 0;
  for (int x0 = 0; x0 < camera.width(); x0 += kSamplesPerPacket) {
    alignas(64) int valid[N];
    alignas(64) Packet packet;
    for (int s = 0; s < kSamplesPerPacket; ++s) {
      const int x = x0 + s;
      const Hit hit = x < camera.width() ? traceCameraRay(rock, camera, x, y, rng) : Hit{};
      for (int k = 0; k < kAoRays; ++k) {
        const int lane = s * kAoRays + k;
        valid[lane] = hit.valid ? -1 : 0;
        setLane(packet, lane, hit.p, hit.valid ? cosineDirection(hit.frame, rng) : Vec3(0, 0, 1),
                rock.rayLength);
      }
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    occluded(valid, rock.scene, &context, &packet);
    for (int lane = 0; lane < N; ++lane)
      if (valid[lane] && packet.tfar[lane] >= 0.f) total += 1.f / kAoRays;
  }
  return total;
}

float rowOccluded1(const EmbreeRock& rock, const PerspectiveCamera& camera, int y, FastRng& rng) {
  float total = 0;
  for (int x = 0; x < camera.width(); ++x) {
    const Hit hit = traceCameraRay(rock, camera, x, y, rng);
    if (!hit.valid) continue;
    for (int k = 0; k < kAoRays; ++k) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      const Vec3 d = cosineDirection(hit.frame, rng);
      RTCRay r;
      setupRay(Ray{hit.p, d, 0.f, rock.rayLength}, rock.rayLength, r);
      rtcOccluded1(rock.scene, &context, &r);
      if (r.tfar >= 0.f) total += 1.f / kAoRays;
    }
  }
  return total;
}

// The row's occlusion rays as one stream; its camera rays one by one, or also as one stream.
float rowStream(const EmbreeRock& rock, const PerspectiveCamera& camera, int y, FastRng& rng,
                std::vector<RTCRay>& rays, std::vector<Ray>& primary, std::vector<RTCRayHit>& primaryHits,
                bool streamCameraRays) {
  if (streamCameraRays) {
    primary.clear();
    primaryHits.resize(size_t(camera.width()));
    for (int x = 0; x < camera.width(); ++x) {
      primary.push_back(jitteredCameraRay(camera, x, y, rng));
      setupRayHit(primary.back(), primary.back().tMax, primaryHits[size_t(x)]);
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect1M(rock.scene, &context, primaryHits.data(), unsigned(primaryHits.size()), sizeof(RTCRayHit));
  }
  rays.clear();
  for (int x = 0; x < camera.width(); ++x) {
    const Hit hit = streamCameraRays ? shadingPoint(primary[size_t(x)], primaryHits[size_t(x)])
                                     : traceCameraRay(rock, camera, x, y, rng);
    if (!hit.valid) continue;
    for (int k = 0; k < kAoRays; ++k) {
      const Vec3 d = cosineDirection(hit.frame, rng);
      RTCRay r;
      setupRay(Ray{hit.p, d, 0.f, rock.rayLength}, rock.rayLength, r);
      rays.push_back(r);
    }
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  rtcOccluded1M(rock.scene, &context, rays.data(), unsigned(rays.size()), sizeof(RTCRay));
  float total = 0;
  for (const RTCRay& r : rays)
    if (r.tfar >= 0.f) total += 1.f / kAoRays;
  return total;
}

enum class Variant { Occluded1, Occluded4, Occluded8, Occluded16, Stream, Streams };

void BM_Yardstick_RockAo(benchmark::State& state) {
  const EmbreeRock& rock = embreeRock();
  const PerspectiveCamera camera(rockScene().settings.camera);
  const auto variant = Variant(state.range(0));
  // Without AVX-512, Embree 3.13 splits a 16-ray packet into 8-ray halves; after rtcOccluded1 calls in
  // the same process, Debian's build then fails its own ray-validity assertion on rays that are valid
  // (finite origins and directions, tnear 0, tfar finite), so the variant runs only where the packet
  // is native.
  if (variant == Variant::Occluded16 &&
      !rtcGetDeviceProperty(rock.device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) {
    state.SkipWithError("rtcOccluded16 is not native on this CPU (no AVX-512)");
    return;
  }
  FastRng rng{0x9E3779B97F4A7C15ULL};
  std::vector<RTCRay> stream;
  stream.reserve(size_t(camera.width()) * kAoRays);
  std::vector<Ray> primary;
  std::vector<RTCRayHit> primaryHits;
  double sum = 0;
  int passes = 0;
  for (auto _ : state) {
    for (int y = 0; y < camera.height(); ++y) {
      switch (variant) {
        case Variant::Occluded1:
          sum += rowOccluded1(rock, camera, y, rng);
          break;
        case Variant::Occluded4:
          sum += pixelsByPackets<4, RTCRay4>(rock, camera, y, rng, rtcOccluded4);
          break;
        case Variant::Occluded8:
          sum += pixelsByPackets<8, RTCRay8>(rock, camera, y, rng, rtcOccluded8);
          break;
        case Variant::Occluded16:
          sum += pixelsByPackets<16, RTCRay16>(rock, camera, y, rng, rtcOccluded16);
          break;
        case Variant::Stream:
        case Variant::Streams:
          sum += rowStream(rock, camera, y, rng, stream, primary, primaryHits, variant == Variant::Streams);
          break;
      }
    }
    ++passes;
  }
  const double pixels = double(camera.width()) * camera.height();
  state.counters["image_mean"] = sum / (double(passes) * pixels);
  state.SetItemsProcessed(int64_t(double(passes) * pixels * kAoRays));
}
BENCHMARK(BM_Yardstick_RockAo)
    ->ArgName("variant")
    ->DenseRange(0, 5)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// The renderer on the same scene as shipped (independent sampler, gaussian filter, 4 cosine rays), in
// whole passes through the progressive engine, one thread: batched (its default, the visibility rays
// of 256 camera samples as one stream) or one camera sample at a time (makeScalarRowRenderer).
void BM_Penumbra_RockAo(benchmark::State& state) {
  const LoadedScene& s = rockScene();
  constexpr uint32_t kPasses = 2;
  const RenderLimits limits{kPasses, 0.0};
  const auto job = std::make_shared<const RenderJob>(s.scene, s.settings, limits);
  Engine engine;
  if (state.range(0) == 0) engine.setRowRendererFactory(makeScalarRowRenderer);
  for (auto _ : state) {
    engine.start(job, limits, 1);
    engine.wait();
  }
  const Image image = engine.film().mean(kPasses);
  double sum = 0;
  for (size_t i = 0; i < image.rgb.size(); i += 3) sum += image.rgb[i];
  state.counters["image_mean"] = sum / double(image.pixelCount());
  state.SetItemsProcessed(int64_t(state.iterations()) * kPasses * int64_t(image.pixelCount()) * kAoRays);
}
BENCHMARK(BM_Penumbra_RockAo)
    ->ArgName("batched")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

}  // namespace
}  // namespace penumbra
