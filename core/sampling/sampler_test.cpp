#include "core/sampling/sampler.h"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace penumbra {
namespace {

std::vector<float> draw(Sampler& s, IVec2 pixel, uint32_t index, int dims) {
  s.startPixelSample(pixel, index);
  std::vector<float> out;
  for (int d = 0; d < dims; ++d) {
    if (d % 3 == 2) {
      out.push_back(s.next1D());
    } else {
      Vec2 u = s.next2D();
      out.push_back(u.x);
      out.push_back(u.y);
    }
  }
  return out;
}

TEST(Sampler, AccessorsKeepConstructorArguments) {
  Sampler s(SamplerKind::Stratified, 16, 99);
  EXPECT_EQ(s.kind(), SamplerKind::Stratified);
  EXPECT_EQ(s.sampleCount(), 16u);
  EXPECT_EQ(s.seed(), 99u);
}

TEST(Sampler, ValuesInUnitIntervalNeverOne) {
  for (SamplerKind k : {SamplerKind::Independent, SamplerKind::Stratified}) {
    for (uint32_t n : {1u, 2u, 9u, 10u, 16u}) {
      Sampler s(k, n, 5);
      for (int px = 0; px < 8; ++px)
        for (uint32_t i = 0; i < 3 * n + 5; ++i)
          for (float u : draw(s, IVec2(px, 3), i, 9)) {
            ASSERT_GE(u, 0.f);
            ASSERT_LT(u, 1.f);
          }
    }
  }
}

TEST(Sampler, DeterministicRegardlessOfCallOrder) {
  for (SamplerKind k :
       {SamplerKind::Independent, SamplerKind::Stratified, SamplerKind::Sobol, SamplerKind::ZSobol}) {
    Sampler a(k, 16, 1234), b(k, 16, 1234);
    std::vector<float> first = draw(a, IVec2(17, 4), 5, 7);
    // b visits other pixels and samples first, in a different order
    draw(b, IVec2(3, 3), 0, 3);
    draw(b, IVec2(17, 4), 6, 10);
    draw(b, IVec2(-2, 100), 5, 1);
    EXPECT_EQ(draw(b, IVec2(17, 4), 5, 7), first);
    EXPECT_EQ(draw(a, IVec2(17, 4), 5, 7), first);
    Sampler other(k, 16, 1235);
    EXPECT_NE(draw(other, IVec2(17, 4), 5, 7), first);
    EXPECT_NE(draw(a, IVec2(17, 5), 5, 7), first);
    EXPECT_NE(draw(a, IVec2(17, 4), 6, 7), first);
  }
}

TEST(Sampler, StratifiedCoversEveryStratum2D) {
  const uint32_t n = 16;
  Sampler s(SamplerKind::Stratified, n, 7);
  for (IVec2 pixel : {IVec2(0, 0), IVec2(5, 9), IVec2(123, 45)}) {
    for (uint32_t epoch = 0; epoch < 3; ++epoch) {  // beyond N samples: every block of N stays stratified
      for (int dim = 0; dim < 4; ++dim) {
        std::set<int> strata;
        for (uint32_t i = epoch * n; i < (epoch + 1) * n; ++i) {
          s.startPixelSample(pixel, i);
          for (int d = 0; d < dim; ++d) s.next2D();
          Vec2 u = s.next2D();
          strata.insert(int(u.x * 4) + 4 * int(u.y * 4));
        }
        EXPECT_EQ(strata.size(), n) << "pixel " << pixel.x << "," << pixel.y << " dim " << dim;
      }
    }
  }
}

TEST(Sampler, StratifiedCoversEveryStratum1DAndRoundsDown2D) {
  const uint32_t n = 10;  // 1-D: 10 strata; 2-D: 3 x 3 grid
  Sampler s(SamplerKind::Stratified, n, 3);
  std::set<int> strata1, strata2;
  for (uint32_t i = 0; i < n; ++i) {
    s.startPixelSample(IVec2(2, 2), i);
    strata1.insert(int(s.next1D() * n));
  }
  for (uint32_t i = 0; i < 9; ++i) {
    s.startPixelSample(IVec2(2, 2), i);
    s.next1D();
    Vec2 u = s.next2D();
    strata2.insert(int(u.x * 3) + 3 * int(u.y * 3));
  }
  EXPECT_EQ(strata1.size(), n);
  EXPECT_EQ(strata2.size(), 9u);
}

TEST(Sampler, StrataAreNotCorrelatedAcrossDimensions) {
  // The stratum sample i gets in dimension 0 should not predict the one in dimension 1.
  Sampler s(SamplerKind::Stratified, 16, 11);
  int identical = 0;
  for (int px = 0; px < 32; ++px) {
    bool same = true;
    for (uint32_t i = 0; i < 16; ++i) {
      s.startPixelSample(IVec2(px, 0), i);
      Vec2 a = s.next2D(), b = s.next2D();
      same = same && int(a.x * 4) == int(b.x * 4) && int(a.y * 4) == int(b.y * 4);
    }
    identical += same;
  }
  EXPECT_LE(identical, 1);
}

TEST(Sampler, IndependentMeanIsOneHalf) {
  Sampler s(SamplerKind::Independent, 4, 1);
  double sum = 0.0;
  int count = 0;
  for (int px = 0; px < 200; ++px)
    for (uint32_t i = 0; i < 50; ++i) {
      s.startPixelSample(IVec2(px, 1), i);
      Vec2 u = s.next2D();
      sum += u.x + u.y + s.next1D();
      count += 3;
    }
  EXPECT_NEAR(sum / count, 0.5, 0.01);
}

}  // namespace
}  // namespace penumbra
