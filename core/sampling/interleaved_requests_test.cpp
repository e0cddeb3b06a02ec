// Interleaved array requests, next2D(j, n, k, m): what an integrator draws when each shading sample
// needs several values (a light selection's choice and the point on the chosen light).
#include <gtest/gtest.h>

#include <bit>
#include <vector>

#include "core/sampling/sampler.h"
#include "core/sampling/sampler_test_support.h"
#include "core/sampling/sobol_sampler.h"

namespace penumbra {
namespace {

// What a loop that interleaves m requests without telling the stream draws: m array requests that
// all take the same request number.
class NaivelyInterleavedSobol : public SobolSampler {
 public:
  using SobolSampler::next2D;
  using SobolSampler::SobolSampler;
  Vec2 next2D(uint32_t j, uint32_t n, uint32_t /*k*/, uint32_t /*m*/) { return SobolSampler::next2D(j, n); }
};

// The m = 2 interleaved requests of n points, then one plain request, against the same three
// requests drawn one after another. Empty when equal bit for bit.
template <class S>
std::string interleavedDefect(S& a, S& b, IVec2 pixel, uint32_t index, uint32_t n) {
  a.startPixelSample(pixel, index);
  b.startPixelSample(pixel, index);
  a.next2D();  // a plain request before, as the pixel filter's
  b.next2D();
  std::vector<Vec2> first(n), second(n);
  for (uint32_t j = 0; j < n; ++j) {
    first[j] = a.next2D(j, n, 0, 2);
    second[j] = a.next2D(j, n, 1, 2);
  }
  for (uint32_t j = 0; j < n; ++j)
    if (b.next2D(j, n) != first[j]) return "request 0, point " + std::to_string(j);
  for (uint32_t j = 0; j < n; ++j)
    if (b.next2D(j, n) != second[j]) return "request 1, point " + std::to_string(j);
  if (a.next2D() != b.next2D()) return "the request after";
  return {};
}

TEST(InterleavedRequests, AreTheRequestsDrawnOneAfterAnother) {
  for (uint32_t n : {1u, 2u, 3u, 4u, 16u})
    for (uint32_t index : {0u, 1u, 5u, 1000u}) {
      SobolSampler a(3), b(3);
      EXPECT_EQ(interleavedDefect(a, b, IVec2(7, 3), index, n), "") << "sobol n " << n;
      ZSobolSampler za(16, 3), zb(16, 3);
      EXPECT_EQ(interleavedDefect(za, zb, IVec2(70, 33), index, n), "") << "zsobol n " << n;
    }
  NaivelyInterleavedSobol a(3), b(3);
  EXPECT_NE(interleavedDefect(a, b, IVec2(7, 3), 1, 4), "");
}

// Each of the two interleaved requests is stratified over a sample's n points and over all of the
// pixel's first 2^k samples; the two are not the same points.
template <class S>
std::string interleavedNetDefect(S& s, IVec2 pixel, uint32_t n, int k) {
  const int log2n = std::bit_width(n) - 1;
  std::vector<Vec2> all0, all1;
  for (uint32_t i = 0; i < (1u << k); ++i) {
    s.startPixelSample(pixel, i);
    s.next2D();
    std::vector<Vec2> one0, one1;
    for (uint32_t j = 0; j < n; ++j) {
      one0.push_back(s.next2D(j, n, 0, 2));
      one1.push_back(s.next2D(j, n, 1, 2));
      if (one0.back() == one1.back()) return "the two requests gave one point";
    }
    if (std::string d = netDefect(one0, log2n); !d.empty()) return "request 0 of one sample: " + d;
    if (std::string d = netDefect(one1, log2n); !d.empty()) return "request 1 of one sample: " + d;
    all0.insert(all0.end(), one0.begin(), one0.end());
    all1.insert(all1.end(), one1.begin(), one1.end());
  }
  if (std::string d = netDefect(all0, k + log2n); !d.empty()) return "request 0 of all samples: " + d;
  if (std::string d = netDefect(all1, k + log2n); !d.empty()) return "request 1 of all samples: " + d;
  return {};
}

TEST(InterleavedRequests, EachIsStratifiedOverTheShadingSamples) {
  for (uint32_t n : {1u, 4u, 16u})
    for (int k : {0, 3, 6}) {
      SobolSampler s(5);
      EXPECT_EQ(interleavedNetDefect(s, IVec2(2, 9), n, k), "") << "sobol n " << n << " k " << k;
      ZSobolSampler z(1u << k, 5);
      EXPECT_EQ(interleavedNetDefect(z, IVec2(2, 9), n, k), "") << "zsobol n " << n << " k " << k;
    }
  NaivelyInterleavedSobol broken(5);
  EXPECT_NE(interleavedNetDefect(broken, IVec2(2, 9), 4, 3), "");
}

// Independent and stratified: the plain stream, so their images do not depend on how a loop
// groups its draws.
TEST(InterleavedRequests, OtherSamplersDrawThePlainStream) {
  for (SamplerKind kind : {SamplerKind::Independent, SamplerKind::Stratified}) {
    Sampler a(kind, 16, 9), b(kind, 16, 9);
    for (uint32_t index : {0u, 3u}) {
      a.startPixelSample(IVec2(4, 5), index);
      b.startPixelSample(IVec2(4, 5), index);
      for (uint32_t j = 0; j < 3; ++j)
        for (uint32_t k = 0; k < 2; ++k) EXPECT_EQ(a.next2D(j, 3, k, 2), b.next2D());
    }
  }
  // The Sampler's Sobol' kinds are the streams above.
  Sampler a(SamplerKind::Sobol, 16, 3);
  SobolSampler b(3);
  a.startPixelSample(IVec2(7, 3), 2);
  b.startPixelSample(IVec2(7, 3), 2);
  for (uint32_t j = 0; j < 4; ++j)
    for (uint32_t k = 0; k < 2; ++k) EXPECT_EQ(a.next2D(j, 4, k, 2), b.next2D(j, 4, k, 2));
}

}  // namespace
}  // namespace penumbra
