#include "core/render/sample_count_fit.h"

#include <bit>

#include "core/sampling/sampler_table.h"
#include "core/sampling/sobol_stream.h"

namespace penumbra {

namespace {

uint32_t floorSqrt(uint32_t n) {
  uint32_t r = 0;
  while ((r + 1) * (r + 1) <= n) ++r;
  return r;
}

}  // namespace

std::string fitSampleCountToTarget(RenderSettings& s, uint32_t targetSpp) {
  if (!samplerRow(s.samplerKind).usesSampleCount) return {};
  if (targetSpp > 0) s.sampleCount = targetSpp;
  const uint32_t n = std::max<uint32_t>(s.sampleCount, 1);
  const std::string count = std::to_string(n);
  if (s.samplerKind == SamplerKind::Stratified) {
    const uint32_t side = floorSqrt(n);
    const std::string grid = std::to_string(side) + "x" + std::to_string(side);
    if (targetSpp == 0)
      return "stratified: the final sample count is not known (time limit or endless accumulation), so the "
             "strata are those of sampleCount " +
             count + " (1-D: " + count + ", 2-D: " + grid + "); every further " + count +
             " samples repeat them with fresh jitter, and beyond them the error falls like independent "
             "sampling's";
    if (side * side != n)
      return "stratified: " + count + " spp is not a square: 1-D dimensions use " + count +
             " strata, 2-D pairs " + grid + " = " + std::to_string(side * side) + "; their remaining " +
             std::to_string(n - side * side) + " samples per pixel repeat the strata with fresh jitter";
    return {};
  }
  if (s.samplerKind == SamplerKind::ZSobol) {
    const uint32_t shared = 1u << zsobolLog2Samples(n);
    if (targetSpp == 0)
      return "zsobol: the final sample count is not known (time limit or endless accumulation): neighbouring "
             "pixels share nets at sampleCount " +
             count + (shared != n ? " rounded up to " + std::to_string(shared) : std::string()) +
             " samples; before and after it each pixel's power-of-two prefixes are nets of their own";
    if (shared != n)
      return "zsobol: " + count + " spp is not a power of two: neighbouring pixels share nets at " +
             std::to_string(shared) + " samples, so at " + count +
             " their errors cancel only partly (each pixel's own power-of-two prefixes are still nets)";
  }
  return {};
}

}  // namespace penumbra
