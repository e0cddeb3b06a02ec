#include "core/lights/light_selection.h"

#include <vector>

namespace penumbra {

double sphereLightPower(const SphereLight& light) {
  const double r = light.sphere.radius;
  const double meanRadiance = (double(light.radiance.x) + light.radiance.y + light.radiance.z) / 3.0;
  const double power = 4.0 * 9.8696044010893586188 * r * r * meanRadiance;  // 4π²r²·L
  return std::isfinite(power) && power > 0.0 ? power : 0.0;
}

UniformLightSelection makeUniformLightSelection(std::span<const SphereLight> lights) {
  return {static_cast<uint32_t>(lights.size())};
}

PowerLightSelection makePowerLightSelection(std::span<const SphereLight> lights) {
  std::vector<double> power(lights.size());
  for (size_t i = 0; i < lights.size(); ++i) power[i] = sphereLightPower(lights[i]);
  return {makeAliasTable(power)};
}

}  // namespace penumbra
