#include "core/sampling/chi2.h"

#include <boost/math/special_functions/gamma.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

#include "core/sampling/rng.h"

namespace penumbra {

namespace {

constexpr double kBinSlack = 1e-5;  // relative slack for samples rounded just past the domain edge
constexpr int kRefineMinDepth = 6;  // forced depth when re-checking a "zero" cell that got samples
constexpr int kBlockCells = 16;     // expected counts: blocks of 16 x 16 cells (see expectedCounts)
constexpr uint64_t kSamplesPerCancelCheck = 1 << 16;
constexpr double kExcessMassTolerance = 1e-4;  // a pdf integrating to more than 1 + this is rejected

// ---- nested adaptive Gauss-Lobatto quadrature ----------------------------------------------------
// Densities are >= 0, so a relative tolerance per subinterval bounds the relative error of the cell;
// an absolute tolerance per unit length (derived from the cell's size and mass) stops the bisection
// where the pdf is ~0 or jagged at float resolution (a jump's position moves in float steps).
struct Adaptive {
  double relTol;
  int maxDepth;
  int minDepth;
};
constexpr Adaptive kInner{1e-6, 24, 0};  // lines: a jump is bisected down to 2^-24 of the cell
constexpr Adaptive kOuter{1e-5, 18, 0};  // cells: 1e-5 relative, far below sampling noise
constexpr double kCellRelTol = 1e-5;     // error target per cell: 1e-5 of its mass ...
constexpr double kCellAbsTol = 1e-8;     // ... or 1e-8 probability (0.01 samples in 10^6)

// 5-point Gauss-Lobatto (exact for degree 7). Its nodes include both endpoints, so a jump anywhere in
// an interval changes the whole-vs-halves comparison (Gauss-Legendre nodes miss the outer 4.7%).
constexpr double kNodes[5] = {-1.0, -0.6546536707079771, 0.0, 0.6546536707079771, 1.0};
constexpr double kWeights[5] = {0.1, 0.5444444444444444, 0.7111111111111111, 0.5444444444444444, 0.1};

template <class F>
double lobatto5(const F& f, double a, double b) {
  double c = 0.5 * (a + b), h = 0.5 * (b - a), sum = 0.0;
  for (int i = 0; i < 5; ++i) sum += kWeights[i] * f(c + h * kNodes[i]);
  return sum * h;
}

// Bisects until the two halves agree with the whole (or maxDepth): a jump in f costs only O(depth)
// evaluations since only the interval holding it keeps splitting.
template <class F>
double adaptive(const F& f, double a, double b, double whole, const Adaptive& cfg, double absTolPerUnit,
                int depth) {
  double m = 0.5 * (a + b);
  double left = lobatto5(f, a, m), right = lobatto5(f, m, b);
  double sum = left + right;
  if (depth >= cfg.maxDepth ||
      (depth >= cfg.minDepth &&
       std::fabs(sum - whole) <= std::max(cfg.relTol * std::fabs(sum), absTolPerUnit * (b - a))))
    return sum;
  return adaptive(f, a, m, left, cfg, absTolPerUnit, depth + 1) +
         adaptive(f, m, b, right, cfg, absTolPerUnit, depth + 1);
}

template <class F>
double integrate1D(const F& f, double a, double b, const Adaptive& cfg, double absTolPerUnit) {
  return adaptive(f, a, b, lobatto5(f, a, b), cfg, absTolPerUnit, 0);
}

// Integral of f(x, y) over [x0, x1] x [y0, y1]: outer over x of inner integrals over y.
template <class F>
double integrate2D(const F& f, double x0, double x1, double y0, double y1, int minDepth) {
  Adaptive inner = kInner, outer = kOuter;
  inner.minDepth = outer.minDepth = minDepth;
  // rough mass from a 5 x 5 tensor rule sets the absolute tolerance of the cell
  double rough =
      lobatto5([&](double x) { return lobatto5([&](double y) { return f(x, y); }, y0, y1); }, x0, x1);
  double tolCell = std::max(kCellRelTol * std::fabs(rough), kCellAbsTol);
  double outerTol = tolCell / (x1 - x0);                      // per unit x
  double innerTol = 0.1 * tolCell / ((x1 - x0) * (y1 - y0));  // per unit y, for each line
  auto g = [&](double x) { return integrate1D([&](double y) { return f(x, y); }, y0, y1, inner, innerTol); };
  return integrate1D(g, x0, x1, outer, outerTol);
}

// Point of the domain at grid coordinates (x, y): plane (x, y) or sphere (phi, w = 1 - cos theta).
inline Vec3 domainPoint(const Chi2Domain& d, double x, double y) {
  if (d.kind == Chi2Domain::Kind::Square) return Vec3(static_cast<float>(x), static_cast<float>(y), 0.f);
  double sinTheta = std::sqrt(std::max(y * (2.0 - y), 0.0));
  return Vec3(static_cast<float>(sinTheta * std::cos(x)), static_cast<float>(sinTheta * std::sin(x)),
              static_cast<float>(1.0 - y));
}

struct Grid {
  int resX, resY;
  double x0, dx, y0, dy;
};

Grid gridFor(const Chi2Domain& d, int res) {
  if (d.kind == Chi2Domain::Kind::Square)
    return {res, res, d.lo, (d.hi - d.lo) / res, d.lo, (d.hi - d.lo) / res};
  return {2 * res, res, 0.0, 2.0 * kPiD / (2 * res), 0.0, d.wMax / res};
}

double integrateCell(const Chi2Domain& d, const PdfFunction& pdf, const Grid& g, int ix, int iy,
                     int minDepth) {
  auto f = [&](double x, double y) {
    double p = pdf(domainPoint(d, x, y));
    return std::isfinite(p) ? p : 0.0;
  };
  double x0 = g.x0 + ix * g.dx, y0 = g.y0 + iy * g.dy;
  return integrate2D(f, x0, x0 + g.dx, y0, y0 + g.dy, minDepth);
}

// Sphere only: the pdf's mass in the region w in [wMax, 2]: 16 azimuthal cells times rows whose
// widths grow geometrically away from wMax (the first is ~1e-14 wide), so a narrow cone's edge at
// wMax is resolved relative to wMax itself, however small it is.
double integrateOutside(const Chi2Domain& d, const PdfFunction& pdf, CancelFlag cancel = nullptr) {
  if (d.kind != Chi2Domain::Kind::Sphere || d.wMax >= 2.0) return 0.0;
  constexpr int nPhi = 16, nRows = 48;
  const double span = 2.0 - d.wMax;
  double sum = 0.0, w0 = d.wMax;
  for (int row = 0; row < nRows; ++row) {
    throwIfCancelled(cancel);
    double w1 = row == nRows - 1 ? 2.0 : d.wMax + span * std::ldexp(1.0, row - nRows + 1);
    Grid g{nPhi, 1, 0.0, 2.0 * kPiD / nPhi, w0, w1 - w0};
    for (int ix = 0; ix < nPhi; ++ix) sum += integrateCell(d, pdf, g, ix, 0, 0);
    w0 = w1;
  }
  return sum;
}

// Expected counts of every cell for n samples, block by block. A block is light when its integral
// and its cells' midpoint sum both expect fewer than minExpected samples: each of its cells then
// expects fewer too, so pooling puts them all in the pooled cell, whose expectation needs only
// their sum. A light block's cells that received samples get their own integral (the zero-support
// check needs it); the others share the rest of the block's integral in proportion to their
// midpoint values, which is all a plot of `expected` needs. Every other cell is integrated alone.
std::vector<double> expectedCounts(const Chi2Domain& d, const PdfFunction& pdf, const Grid& g, double n,
                                   double minExpected, const std::vector<double>& observed,
                                   CancelFlag cancel) {
  std::vector<double> expected(static_cast<size_t>(g.resX) * g.resY, 0.0);
  auto f = [&](double x, double y) {
    double p = pdf(domainPoint(d, x, y));
    return std::isfinite(p) ? p : 0.0;
  };
  const double cellArea = g.dx * g.dy;
  for (int by = 0; by < g.resY; by += kBlockCells) {
    const int yEnd = std::min(by + kBlockCells, g.resY);
    for (int bx = 0; bx < g.resX; bx += kBlockCells) {
      throwIfCancelled(cancel);
      const int xEnd = std::min(bx + kBlockCells, g.resX);
      auto cell = [&](int ix, int iy) -> double& { return expected[static_cast<size_t>(iy) * g.resX + ix]; };
      double midpoints = 0.0;
      bool negative = false;
      for (int iy = by; iy < yEnd; ++iy)
        for (int ix = bx; ix < xEnd; ++ix) {
          double m = f(g.x0 + (ix + 0.5) * g.dx, g.y0 + (iy + 0.5) * g.dy) * cellArea;
          cell(ix, iy) = m;
          midpoints += m;
          negative = negative || m < 0.0;
        }
      const double mass = negative ? 0.0
                                   : integrate2D(f, g.x0 + bx * g.dx, g.x0 + xEnd * g.dx, g.y0 + by * g.dy,
                                                 g.y0 + yEnd * g.dy, 0);
      if (negative || !(n * mass < minExpected && n * midpoints < minExpected)) {
        for (int iy = by; iy < yEnd; ++iy)
          for (int ix = bx; ix < xEnd; ++ix) cell(ix, iy) = n * integrateCell(d, pdf, g, ix, iy, 0);
        continue;
      }
      double rest = mass, restMidpoints = 0.0;
      int restCells = 0;
      for (int iy = by; iy < yEnd; ++iy)
        for (int ix = bx; ix < xEnd; ++ix) {
          if (observed[static_cast<size_t>(iy) * g.resX + ix] > 0.0) {
            cell(ix, iy) = integrateCell(d, pdf, g, ix, iy, 0);
            rest -= cell(ix, iy);
          } else {
            restMidpoints += cell(ix, iy);
            ++restCells;
          }
        }
      rest = std::max(rest, 0.0);
      for (int iy = by; iy < yEnd; ++iy)
        for (int ix = bx; ix < xEnd; ++ix) {
          double& c = cell(ix, iy);
          if (observed[static_cast<size_t>(iy) * g.resX + ix] <= 0.0)
            c = restMidpoints > 0.0 ? rest * c / restMidpoints : rest / restCells;
          c *= n;
        }
    }
  }
  return expected;
}

}  // namespace

const char* chi2Verdict(const Chi2Result& r) {
  return r.accepted ? "accept" : r.inconclusive ? "inconclusive" : "REJECT";
}

double sidakAlpha(double alpha, int testCount) {
  return testCount <= 1 ? alpha : 1.0 - std::pow(1.0 - alpha, 1.0 / testCount);
}

Chi2Domain chi2DomainFor(WarpType type, float param) {
  switch (type) {
    case WarpType::UniformSquare:
      return Chi2Domain::square(0.0, 1.0);
    case WarpType::Tent:
    case WarpType::UniformDisk:
    case WarpType::ConcentricDisk:
      return Chi2Domain::square(-1.0, 1.0);
    case WarpType::UniformSphere:
      return Chi2Domain::sphere(2.0);
    case WarpType::UniformHemisphere:
    case WarpType::CosineHemisphere:
      return Chi2Domain::sphere(1.0);
    case WarpType::UniformCone: {
      float c = std::clamp(param, -1.f, 1.f);
      double w = static_cast<double>(1.f - c);  // exactly the warp's 1 - cos(theta_max)
      return Chi2Domain::sphere(w > 0.0 ? w : 2.0);
    }
    case WarpType::Beckmann: {
      // P(theta) = 1 - exp(-tan^2 / alpha^2): 99.9% of the mass has tan^2 <= alpha^2 ln 1000.
      double a = param > 0.f ? param : 1.0;
      double tan2 = a * a * std::log(1000.0);
      if (!std::isfinite(tan2)) return Chi2Domain::sphere(1.0);                   // the whole hemisphere
      double w = tan2 / (std::sqrt(1.0 + tan2) * (1.0 + std::sqrt(1.0 + tan2)));  // 1 - 1/sqrt(1+tan2)
      return Chi2Domain::sphere(std::min(w, 1.0));
    }
  }
  return Chi2Domain::square(0.0, 1.0);
}

SampleFunction warpSampleFunction(WarpType type, float param) {
  return [type, param](Vec2 u) { return Warp::warp(type, u, param); };
}

PdfFunction warpPdfFunction(WarpType type, float param, double scale) {
  return [type, param, scale](const Vec3& v) { return scale * Warp::pdf(type, v, param); };
}

Chi2Expected integrateCells(const Chi2Domain& domain, const PdfFunction& pdf, int resolution) {
  Grid g = gridFor(domain, std::max(resolution, 1));
  Chi2Expected e;
  e.resX = g.resX;
  e.resY = g.resY;
  e.cells.resize(static_cast<size_t>(g.resX) * g.resY);
  for (int iy = 0; iy < g.resY; ++iy)
    for (int ix = 0; ix < g.resX; ++ix) e.cells[iy * g.resX + ix] = integrateCell(domain, pdf, g, ix, iy, 0);
  e.outside = integrateOutside(domain, pdf);
  return e;
}

double integratePdf(const Chi2Domain& domain, const PdfFunction& pdf, int resolution) {
  Chi2Expected e = integrateCells(domain, pdf, resolution);
  return std::accumulate(e.cells.begin(), e.cells.end(), 0.0) + e.outside;
}

namespace {

// The test proper: `count` samples from next() (a warped point each call), judged by `pdf`.
template <class Next>
Chi2Result chi2Run(const Chi2Domain& domain, uint64_t count, Next&& next, const PdfFunction& pdf,
                   const Chi2Options& options) {
  Chi2Result r;
  r.alphaEffective = sidakAlpha(options.alpha, options.testCount);
  // A NaN bound would make every cell's quadrature bisect to its maximum depth: reject it at once.
  const bool domainValid = domain.kind == Chi2Domain::Kind::Square
                               ? std::isfinite(domain.lo) && std::isfinite(domain.hi) && domain.lo < domain.hi
                               : domain.wMax > 0.0 && domain.wMax <= 2.0;
  if (!domainValid) {
    r.message = "invalid histogram domain (non-finite or empty bounds)";
    return r;
  }
  Grid g = gridFor(domain, std::max(options.resolution, 1));
  r.resX = g.resX;
  r.resY = g.resY;
  const bool rejectedDraws = options.rejectedDraws && domain.kind == Chi2Domain::Kind::Sphere;
  const size_t cellCount = static_cast<size_t>(g.resX) * g.resY;
  r.observed.assign(cellCount, 0.0);

  // ---- histogram ----
  const double spanX = g.dx * g.resX, spanY = g.dy * g.resY;
  const double slackX = kBinSlack * spanX, slackY = kBinSlack * spanY;
  for (uint64_t i = 0; i < count; ++i) {
    if (i % kSamplesPerCancelCheck == 0) throwIfCancelled(options.cancel);
    Vec3 v = next();
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      ++r.invalidSamples;
      continue;
    }
    if (rejectedDraws && v == Vec3(0.f)) {
      r.observedRejected += 1.0;
      continue;
    }
    double x, y;
    if (domain.kind == Chi2Domain::Kind::Square) {
      x = v.x;
      y = v.y;
    } else {
      double r2 = static_cast<double>(v.x) * v.x + static_cast<double>(v.y) * v.y;
      y = v.z > 0.f ? r2 / (1.0 + v.z) : 1.0 - v.z;  // 1 - cos(theta), precise near the pole
      x = std::atan2(static_cast<double>(v.y), static_cast<double>(v.x));
      if (x < 0.0) x += 2.0 * kPiD;
    }
    double fx = (x - g.x0) / g.dx, fy = (y - g.y0) / g.dy;
    bool outside =
        x < g.x0 - slackX || x > g.x0 + spanX + slackX || y < g.y0 - slackY || y > g.y0 + spanY + slackY;
    if (outside) {
      r.observedOutside += 1.0;
      continue;
    }
    int ix = std::clamp(static_cast<int>(std::floor(fx)), 0, g.resX - 1);
    int iy = std::clamp(static_cast<int>(std::floor(fy)), 0, g.resY - 1);
    r.observed[static_cast<size_t>(iy) * g.resX + ix] += 1.0;
  }

  // ---- expected counts ----
  const double n = static_cast<double>(count);
  // A sharp density's quadrature can take seconds inside one cell: with a cancel flag, it is checked at
  // every evaluation, not only between blocks of cells.
  const PdfFunction checkedPdf = options.cancel ? PdfFunction([&pdf, &options](const Vec3& v) {
    throwIfCancelled(options.cancel);
    return pdf(v);
  })
                                                : pdf;
  r.expected = expectedCounts(domain, checkedPdf, g, n, options.minExpected, r.observed, options.cancel);
  r.expectedOutside = n * integrateOutside(domain, checkedPdf, options.cancel);
  throwIfCancelled(options.cancel);
  if (rejectedDraws) {
    // The mass the pdf misses (negative: more than 1, beyond the quadrature's error, is rejected below).
    const double missing = n - std::accumulate(r.expected.begin(), r.expected.end(), r.expectedOutside);
    r.expectedRejected = missing < -kExcessMassTolerance * n ? missing : std::max(missing, 0.0);
  }

  auto reject = [&](std::string why) {
    r.accepted = false;
    r.pValue = 0.0;
    r.message = std::move(why);
    return r;
  };
  char buf[256];
  if (r.invalidSamples > 0) {
    std::snprintf(buf, sizeof buf, "%llu samples are NaN or infinite",
                  static_cast<unsigned long long>(r.invalidSamples));
    return reject(buf);
  }
  if (r.expectedRejected < 0.0) {
    std::snprintf(buf, sizeof buf, "the pdf integrates to %.6g, more than 1", 1.0 - r.expectedRejected / n);
    return reject(buf);
  }
  if (r.observedRejected > 0.0 && r.expectedRejected == 0.0) {
    std::snprintf(buf, sizeof buf, "%.0f draws failed, where the pdf integrates to 1", r.observedRejected);
    return reject(buf);
  }
  if (r.observedOutside > 0.0 && r.expectedOutside == 0.0) {
    std::snprintf(buf, sizeof buf, "%.0f samples fall outside the %s, where the pdf integrates to 0",
                  r.observedOutside, domain.kind == Chi2Domain::Kind::Square ? "square" : "cap");
    return reject(buf);
  }
  // A cell whose integral is exactly 0 but which received samples: make sure the quadrature did not
  // miss a sliver of support (re-integrate on a forced fine grid), then reject.
  int refined = 0;
  for (size_t c = 0; c < cellCount; ++c) {
    if (r.expected[c] != 0.0 || r.observed[c] == 0.0) continue;
    int ix = static_cast<int>(c % g.resX), iy = static_cast<int>(c / g.resX);
    throwIfCancelled(options.cancel);
    if (refined++ < 8) r.expected[c] = n * integrateCell(domain, checkedPdf, g, ix, iy, kRefineMinDepth);
    if (r.expected[c] == 0.0) {
      std::snprintf(buf, sizeof buf, "%.0f samples in cell (%d, %d), where the pdf integrates to 0",
                    r.observed[c], ix, iy);
      return reject(buf);
    }
  }

  // ---- pool small cells (smallest expected first, until the pool expects minExpected) ----
  struct Cell {
    double obs, exp;
  };
  std::vector<Cell> cells;
  cells.reserve(cellCount + 1);
  for (size_t c = 0; c < cellCount; ++c)
    if (r.expected[c] > 0.0) cells.push_back({r.observed[c], r.expected[c]});
  if (r.expectedOutside > 0.0) cells.push_back({r.observedOutside, r.expectedOutside});
  if (r.expectedRejected > 0.0) cells.push_back({r.observedRejected, r.expectedRejected});
  std::sort(cells.begin(), cells.end(), [](const Cell& a, const Cell& b) { return a.exp < b.exp; });
  Cell pool{0.0, 0.0};
  size_t first = 0;
  while (first < cells.size() &&
         (cells[first].exp < options.minExpected || (r.pooledCells > 0 && pool.exp < options.minExpected))) {
    pool.obs += cells[first].obs;
    pool.exp += cells[first].exp;
    ++r.pooledCells;
    ++first;
  }
  double chi2 = 0.0;
  int used = 0;
  if (r.pooledCells > 0) {
    chi2 += (pool.obs - pool.exp) * (pool.obs - pool.exp) / pool.exp;
    ++used;
  }
  for (size_t c = first; c < cells.size(); ++c) {
    chi2 += (cells[c].obs - cells[c].exp) * (cells[c].obs - cells[c].exp) / cells[c].exp;
    ++used;
  }
  r.chi2 = chi2;
  r.dof = used - 1;
  if (r.dof < 1) {
    r.accepted = false;
    r.inconclusive = true;
    r.pValue = std::numeric_limits<double>::quiet_NaN();
    std::snprintf(buf, sizeof buf,
                  "too few samples to test: pooling the cells that expect fewer than %g samples "
                  "leaves fewer than two cells; enlarge the sample count or lower the resolution",
                  options.minExpected);
    r.message = buf;
    return r;
  }
  r.pValue = boost::math::gamma_q(0.5 * r.dof, 0.5 * r.chi2);
  r.accepted = r.pValue >= r.alphaEffective;
  if (!r.accepted) {
    std::snprintf(buf, sizeof buf, "p-value %.3g below the significance level %.3g", r.pValue,
                  r.alphaEffective);
    r.message = buf;
  }
  return r;
}

}  // namespace

Chi2Result chi2Test(const Chi2Domain& domain, const SampleFunction& sample, const PdfFunction& pdf,
                    const Chi2Options& options) {
  Rng rng(mix64(options.seed), options.seed);
  auto next = [&] {
    float u1 = rng.nextFloat();
    return sample(Vec2(u1, rng.nextFloat()));
  };
  return chi2Run(domain, options.sampleCount, next, pdf, options);
}

Chi2Result chi2TestPoints(const Chi2Domain& domain, const std::vector<Vec3>& points, const PdfFunction& pdf,
                          const Chi2Options& options) {
  size_t i = 0;
  auto next = [&] { return points[i++]; };
  return chi2Run(domain, points.size(), next, pdf, options);
}

}  // namespace penumbra
