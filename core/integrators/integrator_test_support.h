// Hand-built scenes for the integrators' unit tests: no XML (core/scene is a layer above), only the
// world's parts. The receiver is the plane z = 0 facing +z, albedo 1 unless stated.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/geometry/procedural_mesh.h"
#include "core/geometry/ray.h"
#include "core/integrators/ao_integrator.h"
#include "core/integrators/direct_integrator.h"
#include "core/integrators/integrator_desc.h"
#include "core/integrators/mis_integrator.h"
#include "core/integrators/normals_integrator.h"
#include "core/lights/mesh_lights.h"
#include "core/lights/sphere_cap.h"
#include "core/math/vec.h"
#include "core/sampling/sampler.h"
#include "core/sampling/sampler_table.h"
#include "core/world/scene.h"

namespace penumbra::test {

// The concrete integrator of a strategy known at compile time, with `samples` shading samples (MIS:
// as both counts), for tests that call Li directly.
template <IntegratorDesc D>
auto integratorOf(int samples) {
  if constexpr (D.type == IntegratorType::Ao)
    return AoIntegrator<D.warp>{samples};
  else if constexpr (D.type == IntegratorType::Simple)
    return SimpleIntegrator{};
  else if constexpr (D.type == IntegratorType::Normals)
    return NormalsIntegrator{};
  else if constexpr (D.estimator == Estimator::Hemisphere)
    return HemisphereDirectIntegrator<D.warp>{samples};
  else if constexpr (D.estimator == Estimator::Bsdf)
    return BsdfDirectIntegrator{samples};
  else if constexpr (D.estimator == Estimator::Light)
    return LightDirectIntegrator<D.lightMeasure, D.lightSelection>{samples};
  else
    return MisIntegrator<D.lightMeasure, D.heuristic>{samples, samples};
}

// Every sampler of the sampler table, in table order: the integrators' tests run with each.
inline std::vector<SamplerKind> everySampler() {
  std::vector<SamplerKind> kinds;
  for (const SamplerRow& row : samplerTable()) kinds.push_back(row.kind);
  return kinds;
}

// Object 0: the square [-half, half]² of the plane z = 0, normal +z.
inline std::unique_ptr<Scene> planeScene(float half = 10.f, Color3 albedo = Color3(1.f)) {
  auto scene = std::make_unique<Scene>();
  scene->geometry.addMesh(
      makeGridPlane(Vec3(-half, -half, 0.f), Vec3(2.f * half, 0.f, 0.f), Vec3(0.f, 2.f * half, 0.f), 1, 1),
      0);
  scene->materials.push_back(SurfaceMaterial{makeDiffuse(albedo)});
  return scene;
}

// Adds a diffuse sphere (or an emitting one when `radiance` is not black) as the next object.
inline void addSphere(Scene& scene, const Vec3& center, float radius, Color3 radiance = Color3(0.f)) {
  SurfaceMaterial material;
  const auto objectId = static_cast<uint32_t>(scene.materials.size());
  const auto index = static_cast<int32_t>(scene.geometry.addSphere(Sphere{center, radius}, objectId));
  if (!isBlack(radiance)) {
    material.bsdf = makeDiffuse(Color3(0.f));
    material.sphereLight = static_cast<int32_t>(scene.sphereLights.size());
    SphereLight light{Sphere{center, radius}, radiance};
    light.geometryIndex = index;
    scene.sphereLights.push_back(light);
  }
  scene.materials.push_back(material);
}

// Adds a one-sided emitting polygon (3 or 4 vertices, convex, emitting towards its counter-clockwise
// winding's normal) as the next object: a triangle fan, made into lights as the scene builder does.
inline void addPolygonLight(Scene& scene, const std::vector<Vec3>& vertices, Color3 radiance) {
  TriangleMesh mesh;
  mesh.positions = vertices;
  for (uint32_t i = 1; i + 1 < vertices.size(); ++i) mesh.triangles.push_back(glm::uvec3(0, i, i + 1));
  SurfaceMaterial material;
  material.bsdf = makeDiffuse(Color3(0.f));
  material.polygonLightsAt = static_cast<int32_t>(scene.polygonLightOfPrim.size());
  addMeshLights(mesh, radiance, scene.polygonLights, scene.polygonLightOfPrim);
  scene.geometry.addMesh(mesh, static_cast<uint32_t>(scene.materials.size()));
  scene.materials.push_back(material);
}

// Builds the queries; call after the last add.
inline void finish(Scene& scene) {
  scene.geometry.build();
  buildLightSelections(scene);
  scene.rayLengthBound = scene.geometry.bounds().diagonal() * 1.01f;
}

// A camera ray straight down onto the point (x, y, 0) of the plane.
inline Ray rayDownOnto(float x, float y) {
  Ray r;
  r.o = Vec3(x, y, 1.f);
  r.d = Vec3(0.f, 0.f, -1.f);
  return r;
}

struct TestSphere {
  Vec3 center;
  float radius;
  float radiance;  // 0: an occluder
};

// The plane z = 0 (albedo 1, half-size `half`) with the spheres (lights and occluders), finished.
inline std::unique_ptr<Scene> planeScene(const std::vector<TestSphere>& spheres, float half = 10.f) {
  auto scene = planeScene(half);
  for (const TestSphere& s : spheres) addSphere(*scene, s.center, s.radius, Color3(s.radiance));
  finish(*scene);
  scene->rayLengthBound = std::max(scene->rayLengthBound, 1e-30f);
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
  return double(radiance) / kPiD * sphereLightIrradianceFactor(cosTheta, sinTheta, sinAlpha, cosAlpha);
}

struct Estimate {
  double mean = 0, standardError = 0;
  double minValue = INFINITY, maxValue = -INFINITY;
  uint64_t bad = 0;  // NaN / Inf / negative values (excluded)
};

// n camera samples of one sampler (independent unless told) of integrator.Li along one ray, red
// channel; the standard error from their spread (conservative for the samplers that stratify).
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
