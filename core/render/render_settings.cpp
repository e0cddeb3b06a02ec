#include "core/render/render_settings.h"

namespace penumbra {

std::vector<std::pair<std::string, std::string>> describeSettings(const RenderSettings& s) {
  std::vector<std::pair<std::string, std::string>> d;
  const IntegratorDesc& in = s.integrator;
  d.emplace_back("integrator", integratorTypeName(in.type));
  if (in.type == IntegratorType::Ao) {
    d.emplace_back("shadingSamples", std::to_string(in.samples));
    d.emplace_back("sampling", in.warp == HemisphereWarp::Uniform ? "uniform" : "cosine");
  } else if (in.type == IntegratorType::Direct) {
    d.emplace_back("nSamples", std::to_string(in.samples));
    d.emplace_back("measure", directMeasureName(in.measure));
    if (in.measure == DirectMeasure::Hemisphere) d.emplace_back("warp-type", hemisphereWarpName(in.warp));
  }
  d.emplace_back("sampler", samplerKindName(s.samplerKind));
  d.emplace_back("sampleCount", std::to_string(s.sampleCount));
  d.emplace_back("seed", std::to_string(s.seed));
  d.emplace_back("rfilter", filterTypeName(s.filter.type));
  d.emplace_back("resolution", std::to_string(s.camera.width) + "x" + std::to_string(s.camera.height));
  return d;
}

}  // namespace penumbra
