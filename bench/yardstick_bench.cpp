// The yardstick, measured in the same run as the renderer: a hand-specialised scalar loop for
// scenes/hw2/Tests/sphere-area.xml against penumbra's general renderer on the same scene. On a shared machine
// whose speed drifts by a third within minutes, "M samples/s" alone says little; the ratio of the
// two, measured seconds apart, says how far the general renderer is from what this scene allows.
//   build/penumbra_bench --benchmark_filter=SphereArea --benchmark_repetitions=5
//     --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
// The target: penumbra on 2 threads ≥ 12 M/s, the loop ~12 M/s on one core, i.e.
// BM_Penumbra_SphereArea/threads:2 ≥ 1.0 × BM_Yardstick_SphereArea.
//
// The loop knows everything in advance: a unit sphere at the origin on the plane z = −1 (200 × 200),
// the camera at (4, 4, 0) looking at the origin (fov 40°, 768²), one light sphere (r = 0.1 at
// (1, −1.5, 1.75), radiance 300), albedo 0.5. Per sample: one jittered camera ray (box filter), the
// light, sphere and plane tested in float, a uniform point on the light sphere, the one shadow test that
// can block (the unit sphere, for plane points), and a float sum per pixel. It has none of the
// renderer's generality or robustness (double-precision sphere roots, scale-aware ray offsets, NaN
// guards, per-pixel variance, the gaussian filter, any scene), which is what the ratio prices.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

#include "bench/fast_rng.h"
#include "core/math/sincos_turns.h"
#include "core/render/engine.h"
#include "core/render/filter.h"
#include "core/render/row_renderer.h"
#include "core/scene/scene_builder.h"

namespace penumbra {
namespace {

constexpr int kSize = 768;

struct Float3 {
  float x, y, z;
};
inline Float3 operator+(Float3 a, Float3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Float3 operator-(Float3 a, Float3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Float3 operator*(float s, Float3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline float dot(Float3 a, Float3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

struct SphereAreaLoop {
  const Float3 eye{4, 4, 0};
  Float3 forward, right, up;
  float tanHalf = std::tan(20.f * kPi / 180.f);
  const Float3 lightCentre{1, -1.5f, 1.75f};
  const float lightRadius = 0.1f;
  // albedo/π · radiance · light area (the area pdf's 1/(4πr²) folded in).
  const float scale = 0.5f / kPi * 300.f * 4.f * kPi * 0.1f * 0.1f;
  std::vector<float> sums = std::vector<float>(size_t(kSize) * kSize, 0.f);

  SphereAreaLoop() {
    // lookat(origin (4,4,0), target 0, up z) as in the scene; the renderer's axis convention.
    const float inv = 1.f / std::sqrt(32.f);
    forward = {-4 * inv, -4 * inv, 0};
    right = {-forward.y, forward.x, 0};  // cross(up (0,0,1), forward): the lookat matrix's first column
    right = (1.f / std::sqrt(dot(right, right))) * right;
    up = {forward.y * right.z - forward.z * right.y, forward.z * right.x - forward.x * right.z,
          forward.x * right.y - forward.y * right.x};
  }

  void pass(FastRng& rng) {
    for (int py = 0; py < kSize; ++py)
      for (int px = 0; px < kSize; ++px) sums[size_t(py) * kSize + px] += sample(px, py, rng);
  }

  // The unit camera ray through image position (sx, sy) in [0, 1]².
  Float3 cameraRay(float sx, float sy) const {
    Float3 d = (1.f - 2.f * sx) * tanHalf * right + (1.f - 2.f * sy) * tanHalf * up + forward;
    return (1.f / std::sqrt(dot(d, d))) * d;
  }

  // The nearest of the unit sphere at the origin and the plane z = −1 along unit d (t = 1e30: none).
  void nearest(Float3 d, float& t, bool& onSphere) const {
    const float b = dot(eye, d), disc = b * b - (dot(eye, eye) - 1.f);
    t = 1e30f;
    onSphere = false;
    if (disc > 0.f) {
      const float t0 = -b - std::sqrt(disc);
      if (t0 > 0.f) t = t0, onSphere = true;
    }
    if (!onSphere && d.z < 0.f) {
      const float tp = (-1.f - eye.z) / d.z;
      const Float3 p = eye + tp * d;
      if (std::fabs(p.x) <= 100.f && std::fabs(p.y) <= 100.f) t = tp;
    }
  }

  // Whether the light is seen directly along d before t (it covers ~1000 pixels and most of the
  // image's mean).
  bool lightFirst(Float3 d, float t) const {
    const Float3 f = eye - lightCentre;
    const float bl = dot(f, d), discL = bl * bl - (dot(f, f) - lightRadius * lightRadius);
    return discL > 0.f && -bl - std::sqrt(discL) < t;
  }

  // Whether the unit sphere (the only thing that can shadow the plane) blocks unit w from plane point p.
  static bool sphereBlocks(Float3 p, Float3 w) {
    const float bb = dot(p, w), dd = bb * bb - (dot(p, p) - 1.f);
    return dd > 0.f && -bb - std::sqrt(dd) > 0.f;
  }

  float sample(int px, int py, FastRng& rng) {
    const float sx = (float(px) + rng.next()) * (1.f / kSize), sy = (float(py) + rng.next()) * (1.f / kSize);
    const Float3 d = cameraRay(sx, sy);
    float t;
    bool onSphere;
    nearest(d, t, onSphere);
    if (lightFirst(d, t)) return 300.f;
    if (t == 1e30f) return 0.f;
    const Float3 p = eye + t * d;
    const Float3 n = onSphere ? p : Float3{0, 0, 1};

    // Uniform point on the light sphere.
    const float z = 1.f - 2.f * rng.next(), r = std::sqrt(std::fmax(0.f, 1.f - z * z));
    const SinCos phi = sinCosTurns(rng.next());
    const Float3 nl{r * phi.cos, r * phi.sin, z};
    const Float3 toL = lightCentre + lightRadius * nl - p;
    const float dist2 = dot(toL, toL), invDist = 1.f / std::sqrt(dist2);
    const float cosS = dot(n, toL) * invDist, cosL = -dot(nl, toL) * invDist;
    if (cosS <= 0.f || cosL <= 0.f) return 0.f;
    if (!onSphere && sphereBlocks(p, invDist * toL)) return 0.f;
    return scale * cosS * cosL / dist2;
  }
};

// The same scene with scenes/hw2/Tests/sphere-solid.xml's strategy and the renderer's own filter: the
// gaussian of the scene, importance-sampled by the renderer's FilterSampler (so both draw the same
// pixel footprint), and a uniform direction in the cone the light subtends, in float. Both loops take
// their azimuths from the renderer's sinCosTurns, the cheapest sin/cos it has.
struct SphereSolidLoop : SphereAreaLoop {
  FilterSampler filter{FilterDesc{}};  // the scene's: gaussian, radius 2, stddev 0.5
  const float albedoRadianceOverPi = 0.5f / kPi * 300.f;

  // Rows [y0, y1) of one pass.
  void pass(FastRng& rng, int y0, int y1) {
    for (int py = y0; py < y1; ++py)
      for (int px = 0; px < kSize; ++px) sums[size_t(py) * kSize + px] += sample(px, py, rng);
  }

  float sample(int px, int py, FastRng& rng) {
    float weight;
    const Vec2 offset = filter.sample(Vec2(rng.next(), rng.next()), weight);
    const Float3 d = cameraRay((float(px) + 0.5f + offset.x) * (1.f / kSize),
                               (float(py) + 0.5f + offset.y) * (1.f / kSize));
    float t;
    bool onSphere;
    nearest(d, t, onSphere);
    if (lightFirst(d, t)) return 300.f * weight;
    if (t == 1e30f) return 0.f;
    const Float3 p = eye + t * d;
    const Float3 n = onSphere ? p : Float3{0, 0, 1};

    // Uniform in the cone towards the light: 1 − cos θ = u (1 − cos θmax), about the axis wc.
    const Float3 toC = lightCentre - p;
    const float dist2 = dot(toC, toC), invDist = 1.f / std::sqrt(dist2);
    const Float3 wc = invDist * toC;
    const float sin2Max = lightRadius * lightRadius / dist2;
    const float oneMinusCosMax = sin2Max / (1.f + std::sqrt(1.f - sin2Max));
    const float oneMinusCos = rng.next() * oneMinusCosMax;
    const float cosT = 1.f - oneMinusCos, sinT = std::sqrt(oneMinusCos * (2.f - oneMinusCos));
    const SinCos phi = sinCosTurns(rng.next());
    // Duff et al.'s branchless basis about wc.
    const float sign = std::copysign(1.f, wc.z), a = -1.f / (sign + wc.z), b = wc.x * wc.y * a;
    const Float3 s{1.f + sign * wc.x * wc.x * a, sign * b, -sign * wc.x};
    const Float3 u{b, sign + wc.y * wc.y * a, -wc.y};
    const Float3 w = (sinT * phi.cos) * s + (sinT * phi.sin) * u + cosT * wc;
    const float cosS = dot(n, w);
    if (cosS <= 0.f) return 0.f;
    if (!onSphere && sphereBlocks(p, w)) return 0.f;
    return albedoRadianceOverPi * cosS * (2.f * kPi * oneMinusCosMax) * weight;
  }
};

void BM_Yardstick_SphereArea(benchmark::State& state) {
  SphereAreaLoop loop;
  FastRng rng{0x9E3779B97F4A7C15ULL};
  int passes = 0;
  for (auto _ : state) {
    loop.pass(rng);
    ++passes;
  }
  double sum = 0;
  for (float v : loop.sums) sum += v;
  state.counters["image_mean"] = sum / (double(passes) * kSize * kSize);  // the scene's: ~0.554
  state.SetItemsProcessed(int64_t(passes) * kSize * kSize);
}
BENCHMARK(BM_Yardstick_SphereArea)->Unit(benchmark::kMillisecond)->UseRealTime();

// The built-in sphere scene by light sampling of `measure`, `passes` whole passes per iteration
// through the progressive engine on state.range(0) threads (`scalar`: one camera sample at a time);
// items are camera samples, and the image mean is reported beside them.
void renderSphereScene(benchmark::State& state, LightMeasure measure, uint32_t passes, bool scalar) {
  LoadedScene s = loadSceneFromString(defaultSceneXml(), "<built-in sphere scene>", ".");
  RenderSettings settings = s.settings;
  settings.integrator = withSamples(directByLight(measure), 1);
  const int threads = int(state.range(0));
  const RenderLimits limits{passes, 0.0};
  const auto job = std::make_shared<const RenderJob>(s.scene, settings, limits);
  Engine engine;
  if (scalar) engine.setRowRendererFactory(makeScalarRowRenderer);
  for (auto _ : state) {
    engine.start(job, limits, threads);
    engine.wait();
  }
  const Image image = engine.film().mean(passes);
  double sum = 0;
  for (size_t i = 0; i < image.rgb.size(); i += 3) sum += image.rgb[i];
  state.counters["image_mean"] = sum / double(image.pixelCount());
  state.SetItemsProcessed(int64_t(state.iterations()) * passes * kSize * kSize);
}

// The sphere-solid loop over `threads` threads (rows split in two halves: the scene's cost is even
// enough across rows), kPasses passes per iteration.
void BM_Yardstick_SphereSolid(benchmark::State& state) {
  constexpr int kPasses = 16;
  const int threads = int(state.range(0));
  SphereSolidLoop loop;
  std::vector<FastRng> rngs;
  for (int i = 0; i < threads; ++i)
    rngs.push_back(FastRng{0x9E3779B97F4A7C15ULL + uint64_t(i) * 0x1234567ULL});
  for (auto _ : state) {
    for (int pass = 0; pass < kPasses; ++pass) {
      std::vector<std::thread> workers;
      for (int i = 0; i < threads; ++i)
        workers.emplace_back([&, i] { loop.pass(rngs[i], kSize * i / threads, kSize * (i + 1) / threads); });
      for (std::thread& w : workers) w.join();
    }
  }
  double sum = 0;
  for (float v : loop.sums) sum += v;
  state.counters["image_mean"] = sum / (double(state.iterations()) * kPasses * kSize * kSize);
  state.SetItemsProcessed(int64_t(state.iterations()) * kPasses * kSize * kSize);
}
BENCHMARK(BM_Yardstick_SphereSolid)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The renderer on scenes/hw2/Tests/sphere-solid.xml (the built-in scene with the solid-angle measure),
// 16 passes of 768² as `penumbra render --spp 16` renders them, in packets (simd:1) or one camera
// sample at a time (simd:0).
void BM_Penumbra_SphereSolid(benchmark::State& state) {
  renderSphereScene(state, LightMeasure::SolidAngle, 16, /*scalar=*/state.range(1) == 0);
}
BENCHMARK(BM_Penumbra_SphereSolid)
    ->ArgNames({"threads", "simd"})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Args({2, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The general renderer on the scene as shipped (gaussian filter, area measure, one shadow ray), in
// whole passes through the progressive engine; items are camera samples.
void BM_Penumbra_SphereArea(benchmark::State& state) {
  renderSphereScene(state, LightMeasure::Area, 8, /*scalar=*/false);
}
BENCHMARK(BM_Penumbra_SphereArea)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace penumbra
