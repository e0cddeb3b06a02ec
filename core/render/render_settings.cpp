#include "core/render/render_settings.h"

namespace penumbra {

std::vector<std::pair<std::string, std::string>> describeSettings(const RenderSettings& s) {
  std::vector<std::pair<std::string, std::string>> d;
  d.emplace_back("integrator", nameOf(s.integrator.type));
  for (const CanonicalProperty& p : canonicalProperties(s.integrator)) d.emplace_back(p.name, p.value);
  d.emplace_back("sampler", samplerKindName(s.samplerKind));
  d.emplace_back("sampleCount", std::to_string(s.sampleCount));
  d.emplace_back("seed", std::to_string(s.seed));
  d.emplace_back("rfilter", filterTypeName(s.filter.type));
  d.emplace_back("resolution", std::to_string(s.camera.width) + "x" + std::to_string(s.camera.height));
  return d;
}

}  // namespace penumbra
