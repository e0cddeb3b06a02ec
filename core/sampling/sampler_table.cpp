#include "core/sampling/sampler_table.h"

#include <array>

namespace penumbra {

namespace {

// In enum order (checked below): the row of kind k is kRows[k], and the viewer lists them so.
constexpr std::array kRows = {
    SamplerRow{
        .kind = SamplerKind::Independent,
        .name = {{"independent"}},
        .label = "independent",
        .description = "A fresh pseudo-random number for every dimension of every sample (PCG32).",
        .usesSampleCount = false,
    },
    SamplerRow{
        .kind = SamplerKind::Stratified,
        .name = {{"stratified"}},
        .label = "stratified",
        .description =
            "Jittered strata: sampleCount strata per 1-D dimension, floor(sqrt(sampleCount))^2 per "
            "2-D pair, in a hashed random order per pixel and dimension; fresh jitter beyond "
            "sampleCount.",
        .usesSampleCount = true,
    },
    SamplerRow{
        .kind = SamplerKind::Sobol,
        .name = {{"sobol"}},
        .label = "sobol",
        .description = "Owen-scrambled Sobol' (Burley 2020), every pair of dimensions its own shuffled "
                       "(0,2)-sequence per pixel: each power-of-two prefix of a pixel's samples is a net, "
                       "whatever the final count.",
        .usesSampleCount = false,
    },
    SamplerRow{
        .kind = SamplerKind::ZSobol,
        .name = {{"zsobol"}},
        .label = "zsobol",
        .description = "Owen-scrambled Sobol' in Morton order of the pixels (Ahmed and Wonka 2020): at "
                       "sampleCount (rounded up to a power of two) samples, neighbouring pixels share one "
                       "net and their errors cancel (blue noise); progressive like sobol.",
        .usesSampleCount = true,
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
