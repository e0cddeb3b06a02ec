// Scenes and per-point estimates for the integrators' unit tests: a diffuse plane z = 0 with sphere
// lights (and occluders) built directly, without the scene layer above this one.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/geometry/procedural_mesh.h"
#include "core/lights/sphere_cap.h"
#include "core/sampling/sampler.h"
#include "core/world/scene.h"

namespace penumbra::test {

struct TestSphere {
  Vec3 center;
  float radius;
  float radiance;  // 0: an occluder
};

// The plane z = 0 (albedo 1, half-size `planeHalf`, two triangles) and the spheres, built as the scene
// builder would.
inline std::unique_ptr<Scene> planeScene(const std::vector<TestSphere>& spheres, float planeHalf = 10.f) {
  auto scene = std::make_unique<Scene>();
  const float h = planeHalf;
  scene->geometry.addMesh(makeGridPlane(Vec3(-h, -h, 0.f), Vec3(2 * h, 0, 0), Vec3(0, 2 * h, 0), 1, 1), 0);
  scene->materials.push_back(SurfaceMaterial{Color3(1.f), -1});
  for (const TestSphere& s : spheres) {
    const uint32_t id = uint32_t(scene->materials.size());
    const int32_t index = int32_t(scene->geometry.addSphere(Sphere{s.center, s.radius}, id));
    SurfaceMaterial m{Color3(0.5f), -1};
    if (s.radiance > 0.f) {
      m.sphereLight = int32_t(scene->sphereLights.size());
      scene->sphereLights.push_back(SphereLight{Sphere{s.center, s.radius}, Color3(s.radiance), index});
    }
    scene->materials.push_back(m);
  }
  scene->geometry.build();
  const Bounds b = scene->geometry.bounds();
  scene->rayLengthBound = std::max(b.diagonal() * 1.01f, 1e-30f);
  return scene;
}

// Reaches x on the plane at a shallow angle, from `reach` away along -x, so the camera ray passes under
// lights near the plane.
inline Ray shallowRayOnto(const Vec3& x, float reach = 1.f) {
  Ray r;
  r.o = x + reach * Vec3(-1.f, 0.f, 1e-4f);
  r.d = glm::normalize(x - r.o);
  return r;
}

// Lr = (albedo/π) Le I(θ, α) at the point x (normal +z) for one sphere light, from the float geometry.
inline double closedFormRadiance(const Vec3& x, const Vec3& center, float radius, float radiance) {
  const DVec3 v = DVec3(center) - DVec3(x);
  const double d = glm::length(v), r = radius;
  if (!(d > r)) return 0.0;
  const double cosTheta = v.z / d, sinTheta = std::hypot(v.x, v.y) / d;
  const double sinAlpha = r / d, cosAlpha = std::sqrt((d - r) * (d + r)) / d;
  return double(radiance) / 3.14159265358979323846 *
         sphereLightIrradianceFactor(cosTheta, sinTheta, sinAlpha, cosAlpha);
}

struct Estimate {
  double mean = 0, standardError = 0;
  double minValue = INFINITY, maxValue = -INFINITY;
  uint64_t bad = 0;  // NaN / Inf / negative values (excluded)
};

// n independent (or stratified) camera samples of integrator.Li along one ray, red channel.
template <class Integrator>
Estimate estimateAlong(const Scene& scene, const Integrator& integrator, const Ray& ray, int n, uint64_t seed,
                       SamplerKind kind = SamplerKind::Independent) {
  Sampler sampler(kind, uint32_t(n), seed);
  double sum = 0, sumSq = 0;
  Estimate e;
  for (int i = 0; i < n; ++i) {
    sampler.startPixelSample(IVec2(7, 11), uint32_t(i));
    const float L = integrator.Li(scene, ray, sampler).x;
    if (!(L >= 0.f) || !std::isfinite(L)) {
      ++e.bad;
      continue;
    }
    sum += L;
    sumSq += double(L) * L;
    e.minValue = std::min(e.minValue, double(L));
    e.maxValue = std::max(e.maxValue, double(L));
  }
  e.mean = sum / n;
  const double var = std::max(0.0, sumSq / n - e.mean * e.mean) * n / (n - 1.0);
  e.standardError = std::sqrt(var / n);
  return e;
}

}  // namespace penumbra::test
