// A procedural scene that grows with n: n sphere lights over a 20 × 20 floor plus n non-emitting
// spheres between them and the floor, on a jittered grid whose cells shrink as n grows (the covered
// fraction of the floor and the total emitted power stay roughly constant). For tests and
// benchmarks of many lights and many spheres; nothing large is stored in git. Deterministic per seed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry/sphere.h"
#include "core/math/vec.h"

namespace penumbra {

struct ScalingSphere {
  Sphere sphere;
  Color3 radiance{0.f};  // 0 for the non-emitting spheres
};

// 2n spheres: lights (radiance > 0, varied over about 20× so power-based selection matters) at
// indices 0, 2, 4, … and blockers at 1, 3, 5, …. The floor is y = 0, |x|, |z| <= 10; everything is
// above it (y > 0).
std::vector<ScalingSphere> scalingSceneSpheres(int lightCount, uint64_t seed = 1);

// The same spheres as a scene file: the floor (built-in `plane`), diffuse albedo 0.5 everywhere, a
// camera looking down at the floor from above one edge, `direct` with solid-angle sampling.
std::string scalingSceneXml(int lightCount, int resolution, int samplesPerPixel, uint64_t seed = 1);

}  // namespace penumbra
