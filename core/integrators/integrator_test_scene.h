// Test fixture of the integrator tests: a receiver sphere (radius 1 at the origin, albedo 1) shaded
// at its top x = (0, 0, 1), normal +z, optionally under one sphere light; and the mean +- standard
// error of an integrator along the ray straight down onto x.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/sampling/sampler.h"
#include "core/world/scene.h"

namespace penumbra::test {

inline constexpr float kRayLengthBound = 100.f;

// The receiver alone (lights may be added before build: call finish()).
inline Scene receiverScene() {
  Scene s;
  s.geometry.addSphere(Sphere{Vec3(0.f), 1.f}, 0);
  s.materials.push_back(SurfaceMaterial{Color3(1.f), -1});
  s.rayLengthBound = kRayLengthBound;
  return s;
}

inline void addSphereLight(Scene& s, const Vec3& center, float radius, float radiance) {
  uint32_t id = uint32_t(s.materials.size());
  SphereLight light;
  light.sphere = Sphere{center, radius};
  light.radiance = Color3(radiance);
  light.geometryIndex = int32_t(s.geometry.addSphere(light.sphere, id));
  s.materials.push_back(SurfaceMaterial{Color3(0.f), int32_t(s.sphereLights.size())});
  s.sphereLights.push_back(light);
}

// The ray onto the receiver's top from just above it.
inline Ray rayOntoTop() {
  Ray r;
  r.o = Vec3(0.f, 0.f, 1.25f);
  r.d = Vec3(0.f, 0.f, -1.f);
  return r;
}

struct Moments {
  double mean = 0, standardError = 0;
  uint64_t bad = 0;  // NaN, Inf or negative values
};

template <class Integrator>
Moments estimateOnTop(const Scene& scene, const Integrator& integrator, int n, uint64_t seed) {
  Sampler sampler(SamplerKind::Independent, 1, seed);
  Ray ray = rayOntoTop();
  double sum = 0, sumSq = 0;
  Moments m;
  for (int i = 0; i < n; ++i) {
    sampler.startPixelSample(IVec2(3, 5), uint32_t(i));
    Color3 L = integrator.Li(scene, ray, sampler);
    if (!(L.x >= 0.f && L.y >= 0.f && L.z >= 0.f) || !std::isfinite(L.x + L.y + L.z)) ++m.bad;
    sum += L.x;
    sumSq += double(L.x) * L.x;
  }
  m.mean = sum / n;
  m.standardError = std::sqrt(std::max(0.0, sumSq / n - m.mean * m.mean) / (n - 1.0));
  return m;
}

}  // namespace penumbra::test
