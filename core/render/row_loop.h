// The row loop, instantiated once per integrator by the dispatch over the strategy axes (row_renderer.cpp):
// per pixel, restart the sample stream, importance-sample the pixel filter, trace the camera ray
// through the integrator and accumulate.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/math/float_util.h"
#include "core/render/row_renderer.h"

namespace penumbra {

// Pixel (x, y)'s sample of `pass`: restarts its sample stream, importance-samples the pixel filter
// (its weight in `weight`) and returns the camera ray.
[[gnu::always_inline]] inline Ray startCameraSample(const PerspectiveCamera& camera,
                                                    const FilterSampler& filter, Sampler& s, int x, int y,
                                                    uint32_t pass, float& weight) {
  s.startPixelSample(IVec2(x, y), pass);
  Vec2 offset = filter.sample(s.next2D(), weight);
  return camera.generateRay(Vec2(float(x) + 0.5f + offset.x, float(y) + 0.5f + offset.y));
}

// The preview of every row loop: one sample per block x block square, written to the whole square.
template <class Integrator>
void previewBlocks(const PerspectiveCamera& camera, const Scene& scene, const Integrator& integrator, int y0,
                   int block, Sampler& sampler, Image& image, const std::atomic<bool>& cancel) {
  const int width = camera.width(), height = camera.height();
  const int y1 = std::min(y0 + block, height);
  for (int x0 = 0; x0 < width; x0 += block) {
    if (cancel.load(std::memory_order_relaxed)) return;
    const int x1 = std::min(x0 + block, width);
    IVec2 centre((x0 + x1) / 2, (y0 + y1) / 2);
    sampler.startPixelSample(centre, 0);
    sampler.next2D();  // keep the dimension layout of a regular camera sample
    Color3 L = integrator.Li(scene, camera.generateRay(Vec2(centre) + Vec2(0.5f)), sampler);
    if (!isValidRadiance(L)) L = Color3(0.f);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) image.set(x, y, L);
  }
}

template <class Integrator>
RowRenderer rowsFor(const RenderJob& job, Integrator integrator) {
  PerspectiveCamera camera(job.settings.camera);
  FilterSampler filter(job.settings.filter);
  const Scene* scene = job.scene.get();
  RowRenderer r;
  r.row = [camera, filter, scene, integrator](int y, uint32_t pass, Sampler& sampler, Film& film,
                                              uint64_t& badSamples, const std::atomic<bool>& cancel) {
    const int width = camera.width();
    // Software pipelining: pixel x + 1's stream, filter offset and camera ray (a serial chain of
    // hashes, a table lookup, a square root and a division) are computed before pixel x's Li, so
    // they overlap with it. Two samplers, because each pixel sample restarts its own stream; the
    // image is the same as computing them in order.
    Sampler next = sampler;
    auto startPixel = [&](Sampler& s, int x, float& weight) {
      return startCameraSample(camera, filter, s, x, y, pass, weight);
    };
    Sampler* current = &sampler;
    Sampler* upcoming = &next;
    float weight;
    Ray ray = startPixel(*current, 0, weight);
    for (int x = 0; x < width; ++x) {
      if (cancel.load(std::memory_order_relaxed)) return;
      float nextWeight = 0.f;
      Ray nextRay;
      if (x + 1 < width) nextRay = startPixel(*upcoming, x + 1, nextWeight);
      Color3 L = integrator.Li(*scene, ray, *current);
      // NaN, Inf or negative radiance is a bug somewhere: count it and add nothing.
      if (isValidRadiance(L))
        film.add(x, y, L * weight);
      else
        ++badSamples;
      ray = nextRay;
      weight = nextWeight;
      std::swap(current, upcoming);
    }
  };
  r.preview = [camera, scene, integrator](int y0, int block, Sampler& sampler, Image& image,
                                          const std::atomic<bool>& cancel) {
    previewBlocks(camera, *scene, integrator, y0, block, sampler, image, cancel);
  };
  return r;
}

}  // namespace penumbra
