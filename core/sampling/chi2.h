// Pearson chi-square goodness-of-fit test of a sample warp against a density: histogram many warped
// samples, integrate the density over every histogram cell, compare. Used by `penumbra warp`, the
// tests and (later) the viewer's warp inspector, which draws `observed` and `expected`.
//
// Domains: 2-D warps are binned on a square ([0,1]^2 or [-1,1]^2); spherical warps in
// (phi, w = 1 - cos(theta)) over [0, 2pi) x [0, wMax], which is (phi, cos theta) binning restricted
// to the cap the warp covers (solid angle d(omega) = d(phi) dw, so densities integrate directly).
// Everything outside the binned region (samples outside the square, or w > wMax) forms one extra
// "outside" cell whose expected count is the integral of the pdf there (0 for a 2-D square).
// A sampler that can fail (a BSDF whose reflected direction falls below the surface) returns the
// zero vector for a failed draw; with Chi2Options::rejectedDraws those draws form one more cell,
// which expects the mass the pdf misses, 1 - (its integral over the sphere).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/math/cancellation.h"
#include "core/math/vec.h"
#include "core/sampling/warp.h"

namespace penumbra {

struct Chi2Domain {
  enum class Kind : uint8_t { Square, Sphere };
  Kind kind = Kind::Square;
  double lo = 0.0, hi = 1.0;  // Square: [lo, hi]^2
  double wMax = 2.0;          // Sphere: 1 - cos(theta) in [0, wMax], wMax in (0, 2]

  static Chi2Domain square(double lo, double hi) { return {Kind::Square, lo, hi, 2.0}; }
  static Chi2Domain sphere(double wMax) { return {Kind::Sphere, 0.0, 1.0, wMax}; }
};

// The natural histogram domain of a warp (beckmann: the cap holding 99.9% of the mass).
Chi2Domain chi2DomainFor(WarpType type, float param);

// Not per-sample hot path: std::function keeps the API open for mismatched or scaled pairs.
using SampleFunction = std::function<Vec3(Vec2)>;
using PdfFunction = std::function<double(const Vec3&)>;

SampleFunction warpSampleFunction(WarpType type, float param);
PdfFunction warpPdfFunction(WarpType type, float param, double scale = 1.0);

struct Chi2Options {
  uint64_t sampleCount = 1'000'000;
  int resolution = 51;  // Square: res x res cells; Sphere: 2 res (phi) x res (w) cells
  uint64_t seed = 1;
  double alpha = 0.01;       // significance level of the whole run
  int testCount = 1;         // number of tests in the run (Sidak correction)
  double minExpected = 5.0;  // cells expecting fewer samples are pooled
  // Sphere only: a zero vector is a failed draw, expected with probability 1 - ∫ pdf (a pdf that
  // integrates to more than 1 is then rejected). Off: every sample must be a direction.
  bool rejectedDraws = false;
  CancelFlag cancel = nullptr;  // set: the test throws Cancelled within a fraction of a second
};

// Sidak-corrected per-test level: 1 - (1 - alpha)^(1 / testCount).
double sidakAlpha(double alpha, int testCount);

struct Chi2Result {
  double chi2 = 0.0;
  int dof = 0;
  double pValue = 0.0;
  double alphaEffective = 0.0;
  bool accepted = false;
  // Too few samples to test: after pooling the cells that expect fewer than minExpected samples,
  // fewer than two cells remain (dof < 1). Neither accepted nor rejected; pValue is NaN.
  bool inconclusive = false;
  std::string message;  // why it was rejected or inconclusive (empty when accepted)

  // Grids, row-major with x fastest: Square (x, y); Sphere (phi, w). Counts, not densities.
  int resX = 0, resY = 0;
  std::vector<double> observed, expected;
  double observedOutside = 0.0, expectedOutside = 0.0;
  double observedRejected = 0.0, expectedRejected = 0.0;  // failed draws (Chi2Options::rejectedDraws)
  int pooledCells = 0;                                    // cells merged into the pooled cell
  uint64_t invalidSamples = 0;                            // NaN/inf samples (any of them rejects)
};

// "accept", "REJECT" or "inconclusive": the CLI's word for the outcome.
const char* chi2Verdict(const Chi2Result& r);

// Runs the test: sampleCount samples from PCG32(seed) through `sample`, judged by `pdf`. The expected
// counts are integrated in blocks of cells: a block expecting fewer than minExpected samples in all
// can only join the pooled cell, so its cells share the block's integral by their midpoint values
// (what `expected` shows) instead of each getting its own quadrature; small sample counts on fine
// grids cost milliseconds instead of seconds. Cells that received samples always get their own.
Chi2Result chi2Test(const Chi2Domain& domain, const SampleFunction& sample, const PdfFunction& pdf,
                    const Chi2Options& options);

// The same test on samples already drawn and warped (e.g. a grid or stratified point set, as the
// viewer's warp inspector draws them); options.sampleCount and options.seed are not used.
Chi2Result chi2TestPoints(const Chi2Domain& domain, const std::vector<Vec3>& points, const PdfFunction& pdf,
                          const Chi2Options& options);

// Expected probability of every cell of the domain's grid (same layout as Chi2Result) and of the
// outside region, by nested adaptive Gauss-Lobatto quadrature (error far below sampling noise).
struct Chi2Expected {
  int resX = 0, resY = 0;
  std::vector<double> cells;
  double outside = 0.0;
};
Chi2Expected integrateCells(const Chi2Domain& domain, const PdfFunction& pdf, int resolution);

// Integral of the pdf over the whole domain including the outside region (should be 1).
double integratePdf(const Chi2Domain& domain, const PdfFunction& pdf, int resolution = 51);

}  // namespace penumbra
