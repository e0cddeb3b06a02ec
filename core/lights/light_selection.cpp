#include "core/lights/light_selection.h"

#include <vector>

namespace penumbra {

double sphereLightPower(const SphereLight& light) {
  const double r = light.sphere.radius;
  const double meanRadiance = (double(light.radiance.x) + light.radiance.y + light.radiance.z) / 3.0;
  const double power = 4.0 * 9.8696044010893586188 * r * r * meanRadiance;  // 4π²r²·L
  return std::isfinite(power) && power > 0.0 ? power : 0.0;
}

LightSummary summarizeLight(const SphereLight& light) {
  return {light.sphere.bounds(), light.sphere.center, sphereLightPower(light), Vec3(0.f, 0.f, 1.f), -1.f};
}

LightSummary summarizeLight(const PolygonLight& light) {
  return {light.bounds(), light.centroid(), polygonLightPower(light), light.n, 1.f};
}

std::vector<LightSummary> summarizeLights(std::span<const SphereLight> lights) {
  std::vector<LightSummary> out;
  out.reserve(lights.size());
  for (const SphereLight& l : lights) out.push_back(summarizeLight(l));
  return out;
}

UniformLightSelection makeUniformLightSelection(std::span<const LightSummary> lights) {
  return {static_cast<uint32_t>(lights.size())};
}

PowerLightSelection makePowerLightSelection(std::span<const LightSummary> lights) {
  std::vector<double> power(lights.size());
  for (size_t i = 0; i < lights.size(); ++i) power[i] = lights[i].power;
  return {makeAliasTable(power)};
}

}  // namespace penumbra
