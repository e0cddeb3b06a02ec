#include "core/sampling/sobol_sampler.h"

#include <gtest/gtest.h>
#include <boost/math/special_functions/gamma.hpp>

#include <vector>

#include "core/sampling/chi2.h"
#include "core/sampling/sampler.h"
#include "core/sampling/sampler_test_support.h"

namespace penumbra {
namespace {

// Deliberately broken randomisations: the tests below must catch them.
struct NoScrambling {  // the plain Sobol' sequence, identical in every pixel
  static uint32_t shuffledReversedIndex(uint32_t reversedIndex, uint32_t) { return reversedIndex; }
  static uint32_t scrambledDigits(uint32_t digits, uint32_t) { return digits; }
};
struct AvalancheScrambling : OwenScrambling {  // a full hash of the value: uniform, but breaks nets
  static uint32_t scrambledDigits(uint32_t digits, uint32_t seed) {
    return static_cast<uint32_t>(mix64(digits ^ (uint64_t{seed} << 32)));
  }
};
// The right scramble seeded without the pixel: every pixel gets the same stream.
class PixelBlindSobol : public SobolSampler {
 public:
  using SobolSampler::SobolSampler;
  void startPixelSample(IVec2, uint32_t index) { SobolSampler::startPixelSample(IVec2(0), index); }
};

// Requests 0, 2, 3 are 2-D, request 1 is 1-D: nets for every power-of-two prefix, any pixel and seed.
template <class S>
std::string firstNetDefect(uint64_t seed, int kMax) {
  S s(seed);
  for (IVec2 pixel : {IVec2(0, 0), IVec2(3, 5), IVec2(640, 479), IVec2(-3, 2)}) {
    for (int k = 0; k <= kMax; ++k) {
      std::vector<Vec2> pair0, pair2, pair3;
      std::vector<float> single1;
      for (uint32_t i = 0; i < (1u << k); ++i) {
        s.startPixelSample(pixel, i);
        pair0.push_back(s.next2D());
        single1.push_back(s.next1D());
        pair2.push_back(s.next2D());
        pair3.push_back(s.next2D());
      }
      for (const auto* points : {&pair0, &pair2, &pair3})
        if (std::string d = netDefect(*points, k); !d.empty()) return "k=" + std::to_string(k) + ": " + d;
      if (std::string d = netDefect1D(single1, k); !d.empty())
        return "k=" + std::to_string(k) + " (1-D): " + d;
    }
  }
  return {};
}

TEST(SobolSampler, EveryPowerOfTwoPrefixIsANetInEveryRequest) {
  for (uint64_t seed : {0ull, 1ull, 7ull, 123456789ull})
    EXPECT_EQ(firstNetDefect<SobolSampler>(seed, 12), "");
  EXPECT_NE(firstNetDefect<BasicSobolSampler<AvalancheScrambling>>(1, 12), "");
}

TEST(SobolSampler, ArraysAreStratifiedWithinAndAcrossSamples) {
  for (uint64_t seed : {1ull, 8ull}) {
    SobolSampler s(seed);
    for (uint32_t n : {1u, 2u, 4u, 16u})
      for (int k : {0, 1, 4, 8}) EXPECT_EQ(arrayNetDefect(s, IVec2(7, 3), n, k), "") << n << " " << k;
  }
  BasicSobolSampler<AvalancheScrambling> broken(1);
  EXPECT_NE(arrayNetDefect(broken, IVec2(7, 3), 4, 4), "");
}

TEST(SobolSampler, EveryAlignedBlockOfSamplesIsANet) {
  SobolSampler s(3);
  for (uint32_t block : {1u, 5u, 1000u})
    for (int k : {3, 8})
      EXPECT_EQ(netDefect(pixelPoints(s, IVec2(9, 4), 1, block << k, 1u << k), k), "") << block << " " << k;
}

TEST(SobolSampler, ValuesInUnitIntervalAndAPureFunctionOfSeedPixelAndIndex) {
  SobolSampler a(42), b(42), c(43);
  auto draw = [](SobolSampler& s, IVec2 p, uint32_t i) { return sampleValues(s, p, i, 6); };
  std::vector<float> first = draw(a, IVec2(17, 4), 5);
  for (float u : first) {
    EXPECT_GE(u, 0.f);
    EXPECT_LT(u, 1.f);
  }
  draw(b, IVec2(3, 3), 0);
  draw(b, IVec2(17, 4), 6);
  EXPECT_EQ(draw(b, IVec2(17, 4), 5), first);
  EXPECT_NE(draw(c, IVec2(17, 4), 5), first);
  EXPECT_NE(draw(a, IVec2(17, 5), 5), first);
  EXPECT_NE(draw(a, IVec2(17, 4), 6), first);
  EXPECT_EQ(a.seed(), 42u);
}

// Across pixels one sample of a pixel is an independent uniform point: chi-square of the 2-D
// projection of every 2-D request, of the 1-D request, and of pairs of different requests.
TEST(SobolSampler, ProjectionsAcrossPixelsAreUniform) {
  const int kTests = 3 * 4;
  Chi2Options opt;
  opt.resolution = 16;
  opt.testCount = kTests;
  PdfFunction uniform = [](const Vec3&) { return 1.0; };
  SobolSampler s(11);
  for (uint32_t index : {0u, 1u, 13u}) {
    std::vector<Vec3> pair0, pair2, cross, single;
    for (int y = 0; y < 200; ++y)
      for (int x = 0; x < 160; ++x) {
        s.startPixelSample(IVec2(x, y), index);
        Vec2 u0 = s.next2D();
        float u1 = s.next1D();
        Vec2 u2 = s.next2D();
        pair0.emplace_back(u0.x, u0.y, 0.f);
        pair2.emplace_back(u2.x, u2.y, 0.f);
        cross.emplace_back(u0.x, u2.y, 0.f);
        single.emplace_back(u1, 0.5f, 0.f);
      }
    for (const auto* pts : {&pair0, &pair2, &cross}) {
      Chi2Result r = chi2TestPoints(Chi2Domain::square(0, 1), *pts, uniform, opt);
      EXPECT_TRUE(r.accepted) << "index " << index << ": " << r.message;
    }
    // 1-D: 100 bins, Pearson chi-square with 99 degrees of freedom.
    std::vector<double> bins(100, 0.0);
    for (const Vec3& p : single) bins[static_cast<size_t>(p.x * 100)] += 1;
    double expected = single.size() / 100.0, chi2 = 0;
    for (double o : bins) chi2 += (o - expected) * (o - expected) / expected;
    EXPECT_GT(boost::math::gamma_q(0.5 * 99, 0.5 * chi2), sidakAlpha(0.01, kTests)) << "1-D, index " << index;
  }
}

// Within one pixel, two different requests are independent nets (padding): their cross projection
// over many samples is uniform too.
TEST(SobolSampler, DifferentRequestsOfOnePixelAreIndependent) {
  Chi2Options opt;
  opt.resolution = 16;
  opt.testCount = 2;
  PdfFunction uniform = [](const Vec3&) { return 1.0; };
  SobolSampler s(5);
  for (IVec2 pixel : {IVec2(1, 1), IVec2(50, 7)}) {
    std::vector<Vec3> cross;
    for (uint32_t i = 0; i < 16384; ++i) {
      s.startPixelSample(pixel, i);
      Vec2 a = s.next2D();
      Vec2 b = s.next2D();
      cross.emplace_back(a.x, b.x, 0.f);
    }
    Chi2Result r = chi2TestPoints(Chi2Domain::square(0, 1), cross, uniform, opt);
    EXPECT_TRUE(r.accepted) << r.message;
  }
}

// The same request of horizontally and vertically neighbouring pixels is uncorrelated.
template <class S>
double worstNeighbourCorrelation(S& s) {
  double worst = 0;
  for (IVec2 step : {IVec2(1, 0), IVec2(0, 1)})
    for (int request : {0, 1}) {
      std::vector<double> a, b;
      for (uint32_t index : {0u, 3u})
        for (int y = 0; y < 128; y += 2)
          for (int x = 0; x < 128; x += 2) {
            Vec2 p = requestPoint(s, IVec2(x, y), index, request),
                 q = requestPoint(s, IVec2(x, y) + step, index, request);
            a.insert(a.end(), {p.x, p.y});
            b.insert(b.end(), {q.x, q.y});
          }
      worst = std::max(worst, std::fabs(correlation(a, b)));
    }
  return worst;
}

TEST(SobolSampler, NeighbouringPixelsAreUncorrelated) {
  SobolSampler s(2);
  const double bound = 5.0 / std::sqrt(2.0 * 2 * 64 * 64);  // five standard errors of a correlation
  EXPECT_LT(worstNeighbourCorrelation(s), bound);
  PixelBlindSobol blind(2);
  EXPECT_GT(worstNeighbourCorrelation(blind), 0.99);
  BasicSobolSampler<NoScrambling> plain(2);
  EXPECT_GT(worstNeighbourCorrelation(plain), 0.99);
}

// The mean over many seeds of a 16-sample estimate is within 4 standard errors of the integral,
// for a 2-D integrand and for a product across two requests (which padding must keep independent).
template <class S>
double unbiasednessZScore(bool acrossRequests) {
  const double exact = acrossRequests ? 0.25 : smoothIntegral();
  const int kSeeds = 4000;
  double sum = 0, sum2 = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    S s(static_cast<uint64_t>(seed));
    double est = 0;
    for (uint32_t i = 0; i < 16; ++i) {
      s.startPixelSample(IVec2(5, 8), i);
      Vec2 u = s.next2D();
      est += acrossRequests ? u.x * s.next2D().x : smoothIntegrand(u);
    }
    est /= 16;
    sum += est;
    sum2 += est * est;
  }
  double mean = sum / kSeeds, var = std::max(sum2 / kSeeds - mean * mean, 0.0);
  double se = std::sqrt(var / (kSeeds - 1));
  return se > 0 ? (mean - exact) / se : (mean == exact ? 0.0 : 1e9);
}

TEST(SobolSampler, EstimatesAreUnbiased) {
  EXPECT_LT(std::fabs(unbiasednessZScore<SobolSampler>(false)), 4.0);
  EXPECT_LT(std::fabs(unbiasednessZScore<SobolSampler>(true)), 4.0);
  EXPECT_GT(std::fabs(unbiasednessZScore<BasicSobolSampler<NoScrambling>>(false)), 4.0);
}

// MSE of a smooth 2-D integrand falls like N^-3 with Owen-scrambled Sobol' points (Owen 1997),
// like N^-1 with independent points.
TEST(SobolSampler, MeanSquaredErrorConvergesFasterThanOneOverN) {
  SobolSampler sobol(9);
  double slope = mseSlope(sobol, 2, 10, 256);
  EXPECT_LE(slope, -1.8);
  // Owen scrambling's own rate: without the value scrambles (index shuffles only, in effect
  // digital shifts) the slope is about -2.1.
  EXPECT_LE(slope, -2.4);
  Sampler independent(SamplerKind::Independent, 1, 9);
  double slopeIndependent = mseSlope(independent, 2, 10, 256);
  EXPECT_NEAR(slopeIndependent, -1.0, 0.2);
  BasicSobolSampler<AvalancheScrambling> broken(9);
  EXPECT_GT(mseSlope(broken, 2, 10, 256), -1.8);
  std::printf("fitted slope of log MSE against log N: sobol %.2f, independent %.2f\n", slope,
              slopeIndependent);
}

}  // namespace
}  // namespace penumbra
