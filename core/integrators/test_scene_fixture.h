// Hand-built scenes for the integrators' unit tests: no XML (core/scene is a layer above), only the
// world's parts. The receiver is the plane z = 0 facing +z, albedo 1 unless stated.
#pragma once

#include <memory>

#include "core/geometry/procedural_mesh.h"
#include "core/geometry/ray.h"
#include "core/world/scene.h"

namespace penumbra::test {

// Object 0: the square [-half, half]² of the plane z = 0, normal +z.
inline std::unique_ptr<Scene> planeScene(float half = 10.f, Color3 albedo = Color3(1.f)) {
  auto scene = std::make_unique<Scene>();
  scene->geometry.addMesh(
      makeGridPlane(Vec3(-half, -half, 0.f), Vec3(2.f * half, 0.f, 0.f), Vec3(0.f, 2.f * half, 0.f), 1, 1),
      0);
  scene->materials.push_back(SurfaceMaterial{albedo});
  return scene;
}

// Adds a diffuse sphere (or an emitting one when `radiance` is not black) as the next object.
inline void addSphere(Scene& scene, const Vec3& center, float radius, Color3 radiance = Color3(0.f)) {
  SurfaceMaterial material;
  const auto objectId = static_cast<uint32_t>(scene.materials.size());
  const auto index = static_cast<int32_t>(scene.geometry.addSphere(Sphere{center, radius}, objectId));
  if (!isBlack(radiance)) {
    material.albedo = Color3(0.f);
    material.sphereLight = static_cast<int32_t>(scene.sphereLights.size());
    SphereLight light{Sphere{center, radius}, radiance};
    light.geometryIndex = index;
    scene.sphereLights.push_back(light);
  }
  scene.materials.push_back(material);
}

// Builds the queries; call after the last add.
inline void finish(Scene& scene) {
  scene.geometry.build();
  scene.rayLengthBound = scene.geometry.bounds().diagonal() * 1.01f;
}

// A camera ray straight down onto the point (x, y, 0) of the plane.
inline Ray rayDownOnto(float x, float y) {
  Ray r;
  r.o = Vec3(x, y, 1.f);
  r.d = Vec3(0.f, 0.f, -1.f);
  return r;
}

}  // namespace penumbra::test
