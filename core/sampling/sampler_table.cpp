#include "core/sampling/sampler_table.h"

#include <algorithm>
#include <array>

#include "core/sampling/sobol_stream.h"

namespace penumbra {

namespace {

// Stratified takes the run's count as its strata: 1-D dimensions n strata, 2-D pairs the largest
// square grid of at most n. Without a known count it keeps the scene's.
SampleCountFit fitStratified(uint32_t sceneCount, uint32_t targetSpp) {
  SampleCountFit fit;
  fit.sampleCount = targetSpp > 0 ? targetSpp : sceneCount;
  const uint32_t n = std::max<uint32_t>(fit.sampleCount, 1);
  const std::string count = std::to_string(n);
  const uint32_t side = stratifiedGridSide(n);
  const std::string grid = std::to_string(side) + "x" + std::to_string(side);
  if (targetSpp == 0)
    fit.note =
        "stratified: the final sample count is not known (time limit or endless accumulation), so the "
        "strata are those of sampleCount " +
        count + " (1-D: " + count + ", 2-D: " + grid + "); every further " + count +
        " samples repeat them with fresh jitter, and beyond them the error falls like independent "
        "sampling's";
  else if (side * side != n)
    fit.note = "stratified: " + count + " spp is not a square: 1-D dimensions use " + count +
               " strata, 2-D pairs " + grid + " = " + std::to_string(side * side) + "; their remaining " +
               std::to_string(n - side * side) + " samples per pixel repeat the strata with fresh jitter";
  return fit;
}

// ZSobol takes the run's count as the one at which neighbouring pixels share a net (rounded up to a
// power of two). Without a known count it keeps the scene's.
SampleCountFit fitZSobol(uint32_t sceneCount, uint32_t targetSpp) {
  SampleCountFit fit;
  fit.sampleCount = targetSpp > 0 ? targetSpp : sceneCount;
  const uint32_t n = std::max<uint32_t>(fit.sampleCount, 1);
  const std::string count = std::to_string(n);
  const uint32_t shared = 1u << zsobolLog2Samples(n);
  if (targetSpp == 0)
    fit.note =
        "zsobol: the final sample count is not known (time limit or endless accumulation): neighbouring "
        "pixels share nets at sampleCount " +
        count + (shared != n ? " rounded up to " + std::to_string(shared) : std::string()) +
        " samples; before and after it each pixel's power-of-two prefixes are nets of their own";
  else if (shared != n)
    fit.note = "zsobol: " + count + " spp is not a power of two: neighbouring pixels share nets at " +
               std::to_string(shared) + " samples, so at " + count +
               " their errors cancel only partly (each pixel's own power-of-two prefixes are still nets)";
  return fit;
}

// In enum order (checked below): the row of kind k is kRows[k], and the viewer lists them so.
constexpr std::array kRows = {
    SamplerRow{
        .kind = SamplerKind::Independent,
        .name = {{"independent"}},
        .label = "independent",
        .description = "A fresh pseudo-random number for every dimension of every sample (PCG32).",
        .fitSampleCount = nullptr,
    },
    SamplerRow{
        .kind = SamplerKind::Stratified,
        .name = {{"stratified"}},
        .label = "stratified",
        .description =
            "Jittered strata: sampleCount strata per 1-D dimension, floor(sqrt(sampleCount))^2 per "
            "2-D pair, in a hashed random order per pixel and dimension; fresh jitter beyond "
            "sampleCount.",
        .fitSampleCount = fitStratified,
    },
    SamplerRow{
        .kind = SamplerKind::Sobol,
        .name = {{"sobol"}},
        .label = "sobol",
        .description = "Owen-scrambled Sobol' (Burley 2020), every pair of dimensions its own shuffled "
                       "(0,2)-sequence per pixel: each power-of-two prefix of a pixel's samples is a net, "
                       "whatever the final count.",
        .fitSampleCount = nullptr,
    },
    SamplerRow{
        .kind = SamplerKind::ZSobol,
        .name = {{"zsobol"}},
        .label = "zsobol",
        .description = "Owen-scrambled Sobol' in Morton order of the pixels (Ahmed and Wonka 2020): at "
                       "sampleCount (rounded up to a power of two) samples, neighbouring pixels share one "
                       "net and their errors cancel (blue noise); progressive like sobol.",
        .fitSampleCount = fitZSobol,
    },
};
static_assert(kRows.size() == size_t(kSamplerKindCount));
static_assert([] {
  for (size_t i = 0; i < kRows.size(); ++i)
    if (size_t(kRows[i].kind) != i) return false;
  return true;
}());

}  // namespace

std::span<const SamplerRow> samplerTable() {
  return kRows;
}

const SamplerRow& samplerRow(SamplerKind kind) {
  return kRows[size_t(kind)];
}

const SamplerRow* findSampler(std::string_view name) {
  for (const SamplerRow& r : kRows)
    if (r.name.accepts(name)) return &r;
  return nullptr;
}

std::string acceptedSamplerNames() {
  std::string out;
  for (const SamplerRow& r : kRows) (out += out.empty() ? "" : ", ") += r.name.joined();
  return out;
}

const char* samplerKindName(SamplerKind kind) {
  return samplerRow(kind).name.canonical().data();
}

bool parseSamplerKind(const std::string& name, SamplerKind& out) {
  const SamplerRow* r = findSampler(name);
  if (r) out = r->kind;
  return r != nullptr;
}

}  // namespace penumbra
