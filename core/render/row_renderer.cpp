#include "core/render/row_renderer.h"

#include <cmath>

#include "core/integrators/ao_integrator.h"
#include "core/integrators/direct_integrator.h"
#include "core/integrators/normals_integrator.h"

namespace penumbra {

namespace {

template <class Integrator>
RowRenderer rowsFor(const RenderJob& job, Integrator integrator) {
  PerspectiveCamera camera(job.settings.camera);
  FilterSampler filter(job.settings.filter);
  const Scene* scene = job.scene.get();
  return [camera, filter, scene, integrator](int y, uint32_t pass, Sampler& sampler, Film& film,
                                             uint64_t& badSamples) {
    const int width = camera.width();
    for (int x = 0; x < width; ++x) {
      sampler.startPixelSample(IVec2(x, y), pass);
      float weight;
      Vec2 offset = filter.sample(sampler.next2D(), weight);
      Ray ray = camera.generateRay(Vec2(float(x) + 0.5f + offset.x, float(y) + 0.5f + offset.y));
      Color3 L = integrator.Li(*scene, ray, sampler);
      // NaN, Inf or negative radiance is a bug somewhere: count it and add nothing.
      if (!(L.x >= 0.f && L.y >= 0.f && L.z >= 0.f && std::isfinite(L.x + L.y + L.z))) {
        ++badSamples;
        continue;
      }
      film.add(x, y, L * weight);
    }
  };
}

}  // namespace

RowRenderer makeRowRenderer(const RenderJob& job) {
  const IntegratorDesc& d = job.settings.integrator;
  switch (d.type) {
    case IntegratorType::Normals: return rowsFor(job, NormalsIntegrator{});
    case IntegratorType::Ao:
      if (d.warp == HemisphereWarp::Uniform) return rowsFor(job, AoIntegrator<HemisphereWarp::Uniform>{d.samples});
      return rowsFor(job, AoIntegrator<HemisphereWarp::Cosine>{d.samples});
    case IntegratorType::Simple: return rowsFor(job, DirectIntegrator<DirectStrategy::DeltaOnly>{d.samples});
    case IntegratorType::Direct:
      switch (d.measure) {
        case DirectMeasure::Hemisphere:
          if (d.warp == HemisphereWarp::Uniform)
            return rowsFor(job, DirectIntegrator<DirectStrategy::UniformHemisphere>{d.samples});
          return rowsFor(job, DirectIntegrator<DirectStrategy::CosineHemisphere>{d.samples});
        case DirectMeasure::Area: return rowsFor(job, DirectIntegrator<DirectStrategy::Area>{d.samples});
        case DirectMeasure::SolidAngle:
          return rowsFor(job, DirectIntegrator<DirectStrategy::SolidAngle>{d.samples});
      }
  }
  return rowsFor(job, NormalsIntegrator{});
}

}  // namespace penumbra
