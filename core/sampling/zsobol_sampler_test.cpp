#include "core/sampling/sobol_sampler.h"

#include <gtest/gtest.h>
#include <boost/math/special_functions/gamma.hpp>

#include <vector>

#include "core/sampling/chi2.h"
#include "core/sampling/sampler_test_support.h"

namespace penumbra {
namespace {

// A sampler with the (sampleCount, seed) constructor of zsobol for the generic checks.
template <uint32_t kSampleCount>
class ZSobolWithCount : public ZSobolSampler {
 public:
  explicit ZSobolWithCount(uint64_t seed) : ZSobolSampler(kSampleCount, seed) {}
};

TEST(ZSobolSampler, SampleCountRoundsUpToAPowerOfTwo) {
  EXPECT_EQ(ZSobolSampler(0, 1).log2Samples(), 0u);
  EXPECT_EQ(ZSobolSampler(1, 1).log2Samples(), 0u);
  EXPECT_EQ(ZSobolSampler(4, 1).log2Samples(), 2u);
  EXPECT_EQ(ZSobolSampler(5, 1).log2Samples(), 3u);
  EXPECT_EQ(ZSobolSampler(1u << 30, 1).log2Samples(), kZSobolMaxLog2Samples);
}

// Every pixel's first 2^k samples are nets in every request, below, at and beyond the run's count.
TEST(ZSobolSampler, EveryPowerOfTwoPrefixOfAPixelIsANet) {
  for (uint32_t count : {1u, 4u, 16u, 64u}) {
    ZSobolSampler s(count, 3);
    for (IVec2 pixel : {IVec2(0, 0), IVec2(3, 5), IVec2(640, 479), IVec2(-3, 2)})
      for (int k = 0; k <= 12; ++k) {
        std::vector<Vec2> pair0, pair2;
        std::vector<float> single1;
        for (uint32_t i = 0; i < (1u << k); ++i) {
          s.startPixelSample(pixel, i);
          pair0.push_back(s.next2D());
          single1.push_back(s.next1D());
          pair2.push_back(s.next2D());
        }
        ASSERT_EQ(netDefect(pair0, k), "") << "count " << count << " k " << k;
        ASSERT_EQ(netDefect(pair2, k), "") << "count " << count << " k " << k;
        ASSERT_EQ(netDefect1D(single1, k), "") << "count " << count << " k " << k;
      }
  }
}

// At the run's count 2^m, the samples of every aligned 2^j x 2^j tile of pixels together form a
// (0, m + 2j, 2)-net: what spreads the error of neighbouring pixels like blue noise.
template <class S>
std::string tileNetDefect(S& s, int m, int j, IVec2 tile) {
  for (int request : {0, 2}) {
    std::vector<Vec2> points;
    for (int dy = 0; dy < (1 << j); ++dy)
      for (int dx = 0; dx < (1 << j); ++dx) {
        std::vector<Vec2> p = pixelPoints(s, tile * (1 << j) + IVec2(dx, dy), request, 0, 1u << m);
        points.insert(points.end(), p.begin(), p.end());
      }
    if (std::string d = netDefect(points, m + 2 * j); !d.empty()) return d;
  }
  return {};
}

TEST(ZSobolSampler, AlignedPixelTilesShareOneNetAtTheRunsCount) {
  for (int m = 0; m <= 4; ++m)
    for (uint64_t seed : {1ull, 99ull}) {
      ZSobolSampler s(1u << m, seed);
      for (int j = 1; j <= 3; ++j)
        for (IVec2 tile : {IVec2(0, 0), IVec2(1, 2), IVec2(5, 3)})
          EXPECT_EQ(tileNetDefect(s, m, j, tile), "") << "m " << m << " j " << j;
    }
  // Independently scrambled pixels (sobol) do not.
  SobolSampler sobol(1);
  EXPECT_NE(tileNetDefect(sobol, 2, 1, IVec2(0, 0)), "");
}

TEST(ZSobolSampler, ArraysAreStratifiedWithinAndAcrossSamplesAndTiles) {
  for (uint32_t count : {1u, 4u, 8u}) {
    ZSobolSampler s(count, 5);
    for (uint32_t n : {1u, 2u, 4u, 16u})
      for (int k : {0, 1, 4, 8})
        EXPECT_EQ(arrayNetDefect(s, IVec2(7, 3), n, k), "") << count << " " << n << " " << k;
    // A 2 x 2 tile's arrays at the run's count together form one net.
    const uint32_t n = 4;
    std::vector<Vec2> tile;
    for (IVec2 p : {IVec2(4, 6), IVec2(5, 6), IVec2(4, 7), IVec2(5, 7)})
      for (uint32_t i = 0; i < count; ++i) {
        s.startPixelSample(p, i);
        s.next2D();
        for (uint32_t j = 0; j < n; ++j) tile.push_back(s.next2D(j, n));
      }
    EXPECT_EQ(netDefect(tile, static_cast<int>(s.log2Samples()) + 2 + 2), "") << count;
  }
}

// Blue noise: the errors of horizontally neighbouring pixels at the run's count are negatively
// correlated (they cancel in the 2 x 2 average); sobol's are uncorrelated.
template <class S>
double neighbourErrorCorrelation(S& s, uint32_t count) {
  std::vector<double> a, b;
  const double exact = smoothIntegral();
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; x += 2) {
      a.push_back(pixelEstimate(s, IVec2(x, y), 0, count) - exact);
      b.push_back(pixelEstimate(s, IVec2(x + 1, y), 0, count) - exact);
    }
  return correlation(a, b);
}

TEST(ZSobolSampler, ErrorsOfNeighbouringPixelsCancel) {
  ZSobolSampler z(4, 17);
  SobolSampler sobol(17);
  double zc = neighbourErrorCorrelation(z, 4), sc = neighbourErrorCorrelation(sobol, 4);
  std::printf("error correlation of horizontal neighbours at 4 spp: zsobol %.3f, sobol %.3f\n", zc, sc);
  EXPECT_LT(zc, -0.2);
  EXPECT_LT(std::fabs(sc), 5.0 / std::sqrt(2048.0));
}

TEST(ZSobolSampler, ProjectionsAcrossPixelsAreUniform) {
  Chi2Options opt;
  opt.resolution = 16;
  opt.testCount = 4;
  PdfFunction uniform = [](const Vec3&) { return 1.0; };
  for (uint32_t count : {1u, 16u})
    for (uint32_t index : {0u, 5u}) {
      ZSobolSampler s(count, 4);
      std::vector<Vec3> pair, cross;
      for (int y = 0; y < 160; ++y)
        for (int x = 0; x < 160; ++x) {
          s.startPixelSample(IVec2(x, y), index);
          Vec2 u0 = s.next2D();
          Vec2 u1 = s.next2D();
          pair.emplace_back(u1.x, u1.y, 0.f);
          cross.emplace_back(u0.x, u1.y, 0.f);
        }
      EXPECT_TRUE(chi2TestPoints(Chi2Domain::square(0, 1), pair, uniform, opt).accepted)
          << count << " " << index;
      EXPECT_TRUE(chi2TestPoints(Chi2Domain::square(0, 1), cross, uniform, opt).accepted)
          << count << " " << index;
    }
}

// Correlation of the same request and sample index of pixel p and pixel p + step (p even).
template <class S>
double sampleCorrelation(S& s, IVec2 step) {
  std::vector<double> a, b;
  for (uint32_t index : {0u, 1u, 2u, 3u})
    for (int y = 0; y < 64; y += 2)
      for (int x = 0; x < 64; x += 2) {
        Vec2 p = requestPoint(s, IVec2(x, y), index, 1), q = requestPoint(s, IVec2(x, y) + step, index, 1);
        a.insert(a.end(), {p.x, p.y});
        b.insert(b.end(), {q.x, q.y});
      }
  return correlation(a, b);
}

// Pixels apart are uncorrelated. Neighbours are points of one net, so their values are, by
// construction, negatively correlated (never positively, never equal).
TEST(ZSobolSampler, DistantPixelsAreUncorrelatedAndNeighboursAnticorrelated) {
  const double bound = 5.0 / std::sqrt(4.0 * 2 * 32 * 32);
  for (uint32_t count : {1u, 4u, 64u}) {
    ZSobolSampler s(count, 8);
    for (IVec2 step : {IVec2(16, 0), IVec2(0, 16), IVec2(5, 7)})
      EXPECT_LT(std::fabs(sampleCorrelation(s, step)), bound) << count;
    for (IVec2 step : {IVec2(1, 0), IVec2(0, 1), IVec2(1, 1)}) {
      double c = sampleCorrelation(s, step);
      std::printf("count %u, neighbour (%d, %d): correlation %.3f\n", count, step.x, step.y, c);
      EXPECT_LT(c, bound) << count;
    }
  }
}

// A stream that ignored the pixel would fail the test above.
class PixelBlindZSobol : public ZSobolSampler {
 public:
  using ZSobolSampler::ZSobolSampler;
  void startPixelSample(IVec2, uint32_t index) { ZSobolSampler::startPixelSample(IVec2(0), index); }
};
TEST(ZSobolSampler, APixelBlindStreamIsCorrelated) {
  PixelBlindZSobol blind(4, 8);
  EXPECT_GT(sampleCorrelation(blind, IVec2(16, 0)), 0.99);
}

TEST(ZSobolSampler, APureFunctionOfSeedPixelAndIndex) {
  ZSobolSampler a(16, 42), b(16, 42), c(16, 43);
  auto draw = [](ZSobolSampler& s, IVec2 p, uint32_t i) { return sampleValues(s, p, i, 4); };
  // (81, 4) lies in the second 64 x 64 tile of the first row of tiles.
  std::vector<float> first = draw(a, IVec2(81, 4), 21);
  // b visits the first tile, another row of tiles, other pixels of the tile and other indices first
  draw(b, IVec2(3, 3), 0);
  draw(b, IVec2(100, 70), 21);
  draw(b, IVec2(81, 4), 6);
  draw(b, IVec2(17, 4), 21);
  EXPECT_EQ(draw(b, IVec2(81, 4), 21), first);
  EXPECT_EQ(draw(a, IVec2(81, 4), 21), first);
  EXPECT_NE(draw(c, IVec2(81, 4), 21), first);
  EXPECT_NE(draw(a, IVec2(81, 5), 21), first);
  EXPECT_NE(draw(a, IVec2(81, 4), 22), first);
  // (17, 4) is the same place of the first tile: only the tiles' own randomisations tell them apart
  EXPECT_NE(draw(a, IVec2(17, 4), 21), first);
}

TEST(ZSobolSampler, OneDimensionalRequestsAcrossPixelsAreUniform) {
  for (uint32_t count : {1u, 16u}) {
    ZSobolSampler s(count, 4);
    std::vector<double> bins(100, 0.0);
    for (int y = 0; y < 160; ++y)
      for (int x = 0; x < 160; ++x) {
        s.startPixelSample(IVec2(x, y), 3);
        s.next2D();
        bins[static_cast<size_t>(s.next1D() * 100)] += 1;
      }
    double expected = 160.0 * 160.0 / 100.0, chi2 = 0;
    for (double o : bins) chi2 += (o - expected) * (o - expected) / expected;
    EXPECT_GT(boost::math::gamma_q(0.5 * 99, 0.5 * chi2), sidakAlpha(0.01, 2)) << count;
  }
}

TEST(ZSobolSampler, EstimatesAreUnbiased) {
  const double exact = smoothIntegral();
  const int kSeeds = 4000;
  double sum = 0, sum2 = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    ZSobolSampler s(16, static_cast<uint64_t>(seed));
    double est = pixelEstimate(s, IVec2(6, 9), 1, 16);
    sum += est;
    sum2 += est * est;
  }
  double mean = sum / kSeeds, se = std::sqrt((sum2 / kSeeds - mean * mean) / (kSeeds - 1));
  EXPECT_LT(std::fabs(mean - exact), 4 * se);
}

TEST(ZSobolSampler, MeanSquaredErrorConvergesFasterThanOneOverN) {
  ZSobolWithCount<1> below(9);      // every count beyond the run's count
  ZSobolWithCount<1024> within(9);  // every count up to the run's count
  double slopeBelow = mseSlope(below, 2, 10, 256), slopeWithin = mseSlope(within, 2, 10, 256);
  std::printf("fitted slope of log MSE against log N: zsobol %.2f (count 1), %.2f (count 1024)\n", slopeBelow,
              slopeWithin);
  EXPECT_LE(slopeBelow, -1.8);
  EXPECT_LE(slopeWithin, -1.8);
  // Owen scrambling's own rate (about -2.1 to -2.3 without the value scrambles).
  EXPECT_LE(std::max(slopeBelow, slopeWithin), -2.4);
}

}  // namespace
}  // namespace penumbra
