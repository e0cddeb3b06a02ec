#include "app/ui/warp_inspector_model.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/math/error.h"
#include "core/sampling/rng.h"

namespace penumbra::ui {

namespace {

struct Cancelled {};

// Densities used as "mismatched" judges (all integrate to 1 over their own domain).
double uniformOnSquare(const Vec3& v, double lo, double hi) {
  return v.x >= lo && v.x <= hi && v.y >= lo && v.y <= hi ? 1.0 / ((hi - lo) * (hi - lo)) : 0.0;
}

}  // namespace

const char* pointSetName(PointSet s) {
  switch (s) {
    case PointSet::Independent:
      return "independent";
    case PointSet::Grid:
      return "grid";
    case PointSet::Stratified:
      return "stratified";
    case PointSet::Sampler:
      return "sampler";
  }
  return "?";
}

bool parsePointSet(const std::string& name, PointSet& out) {
  for (int i = 0; i < kPointSetCount; ++i)
    if (name == pointSetName(static_cast<PointSet>(i))) {
      out = static_cast<PointSet>(i);
      return true;
    }
  return false;
}

std::string enterWarpParam(WarpInspectorSettings& s, double value) {
  try {
    s.param = checkedWarpParam(s.type, true, value, "the parameter");
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

std::string enterLog2Points(WarpInspectorSettings& s, int64_t log2Points) {
  try {
    s.log2Points = checkedLog2Points(log2Points, "points");
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

std::string enterSamplerRequest(WarpInspectorSettings& s, int64_t request) {
  try {
    s.request = checkedSamplerRequest(request, "2-D request");
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

std::string enterSamplerPixel(WarpInspectorSettings& s, int64_t x, int64_t y) {
  try {
    const IVec2 p = checkedSamplerPixel(x, y, "pixel");
    s.pixelX = p.x, s.pixelY = p.y;
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

BsdfWarpInputs bsdfInputsOf(const WarpInspectorSettings& s) {
  BsdfWarpInputs in;
  in.type = s.bsdfType == BsdfType::RoughConductor ? "roughconductor" : "microfacet";
  in.distribution = s.distribution == MicrofacetDistribution::Ggx ? "ggx" : "beckmann";
  in.alpha = s.alpha;
  in.kd = s.kd;
  in.incidentDegrees = s.incidentDegrees;
  in.intIOR = s.intIOR;
  in.extIOR = s.extIOR;
  return in;
}

BsdfWarp bsdfWarpOf(const WarpInspectorSettings& s) {
  return checkedBsdfWarp(bsdfInputsOf(s));
}

std::string enterBsdf(WarpInspectorSettings& s, const BsdfWarpInputs& in) {
  try {
    const BsdfWarp w = checkedBsdfWarp(in);
    s.bsdf = true;
    s.bsdfType = w.bsdf.type;
    s.distribution = w.bsdf.distribution;
    s.alpha = w.bsdf.alpha;
    s.kd = float(in.kd);
    s.incidentDegrees = w.incidentDegrees;
    s.intIOR = float(in.intIOR);
    s.extIOR = float(in.extIOR);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

bool showsSphere(const WarpInspectorSettings& s) {
  return s.bsdf || warpIsSpherical(s.type);
}

SampleFunction inspectorSample(const WarpInspectorSettings& s) {
  if (s.bsdf) return bsdfSampleFunction(bsdfWarpOf(s));
  return warpSampleFunction(s.type, s.param);
}

Chi2Domain inspectorDomain(const WarpInspectorSettings& s) {
  return s.bsdf ? bsdfChi2Domain() : chi2DomainFor(s.type, s.param);
}

std::string inspectedName(const WarpInspectorSettings& s) {
  if (!s.bsdf) return warpTypeName(s.type);
  char buf[96];
  if (s.bsdfType == BsdfType::Microfacet)
    std::snprintf(buf, sizeof buf, "microfacet alpha %.3g kd %.3g at %.3g deg", s.alpha, s.kd,
                  s.incidentDegrees);
  else
    std::snprintf(buf, sizeof buf, "roughconductor %s alpha %.3g at %.3g deg",
                  s.distribution == MicrofacetDistribution::Ggx ? "ggx" : "beckmann", s.alpha,
                  s.incidentDegrees);
  return buf;
}

int inspectorResolution(const WarpInspectorSettings& s) {
  if (s.resolution > 0) return s.resolution;
  // About 25 samples per cell on average (sampling noise ~20 % per cell in the panels), 4 ... 64.
  double n = std::ldexp(1.0, s.log2Points);
  double res = showsSphere(s) ? std::sqrt(n / 50.0) : std::sqrt(n / 25.0);
  return std::clamp(static_cast<int>(std::lround(res)), 4, 64);
}

std::string judgeDescription(const WarpInspectorSettings& s) {
  if (!s.mismatch) return "its own pdf";
  char buf[96];
  if (s.bsdf) {
    std::snprintf(buf, sizeof buf, "the pdf at twice the roughness (alpha %.3g)", 2.0 * s.alpha);
    return buf;
  }
  switch (s.type) {
    case WarpType::UniformSquare:
      return "the tent pdf";
    case WarpType::Tent:
    case WarpType::UniformDisk:
    case WarpType::ConcentricDisk:
      return "uniform on [-1,1]^2";
    case WarpType::UniformSphere:
      return "uniform on the upper hemisphere";
    case WarpType::UniformHemisphere:
      return "the cosine-hemisphere pdf";
    case WarpType::CosineHemisphere:
      return "uniform on the hemisphere";
    case WarpType::UniformCone:
      std::snprintf(buf, sizeof buf, "a narrower cone (cos %.3g)", 0.5 * (s.param + 1.0));
      return buf;
    case WarpType::Beckmann:
      std::snprintf(buf, sizeof buf, "beckmann alpha %.3g", 2.0 * s.param);
      return buf;
  }
  return "?";
}

PdfFunction judgePdf(const WarpInspectorSettings& s) {
  if (s.bsdf) {
    BsdfWarp w = bsdfWarpOf(s);
    if (s.mismatch) w.bsdf.alpha = std::min(2.f * w.bsdf.alpha, kMaxAlpha);
    return bsdfPdfFunction(w);
  }
  const float p = s.param;
  if (!s.mismatch) return warpPdfFunction(s.type, p);
  switch (s.type) {
    case WarpType::UniformSquare:
      return warpPdfFunction(WarpType::Tent, 0.f);
    case WarpType::Tent:
    case WarpType::UniformDisk:
    case WarpType::ConcentricDisk:
      return [](const Vec3& v) { return uniformOnSquare(v, -1.0, 1.0); };
    case WarpType::UniformSphere:
      return warpPdfFunction(WarpType::UniformHemisphere, 0.f);
    case WarpType::UniformHemisphere:
      return warpPdfFunction(WarpType::CosineHemisphere, 0.f);
    case WarpType::CosineHemisphere:
      return warpPdfFunction(WarpType::UniformHemisphere, 0.f);
    case WarpType::UniformCone:
      return warpPdfFunction(WarpType::UniformCone, 0.5f * (p + 1.f));
    case WarpType::Beckmann:
      return warpPdfFunction(WarpType::Beckmann, 2.f * p);
  }
  return warpPdfFunction(s.type, p);
}

std::vector<Vec2> makeSamplerPointSet(SamplerKind kind, int log2Points, uint64_t seed, int request,
                                      IVec2 pixel) {
  const int k = std::clamp(log2Points, 0, 30);
  Sampler sampler(kind, 1u << k, seed);
  std::vector<Vec2> pts(size_t(1) << k);
  for (size_t i = 0; i < pts.size(); ++i) {
    sampler.startPixelSample(pixel, uint32_t(i));
    for (int r = 0; r < request; ++r) sampler.next2D();
    pts[i] = sampler.next2D();
  }
  return pts;
}

std::vector<Vec2> makePointSet(const WarpInspectorSettings& s) {
  if (s.pointSet == PointSet::Sampler)
    return makeSamplerPointSet(s.sampler, s.log2Points, s.seed, s.request, IVec2(s.pixelX, s.pixelY));
  return makePointSet(s.pointSet, s.log2Points, s.seed);
}

std::vector<Vec2> makePointSet(PointSet set, int log2Points, uint64_t seed) {
  const int k = std::clamp(log2Points, 0, 30);
  const size_t n = size_t(1) << k;
  std::vector<Vec2> pts(n);
  Rng rng(mix64(seed), seed);
  if (set == PointSet::Independent) {
    for (size_t i = 0; i < n; ++i) {
      float u1 = rng.nextFloat();
      pts[i] = Vec2(u1, rng.nextFloat());
    }
    return pts;
  }
  const int nx = 1 << ((k + 1) / 2), ny = 1 << (k / 2);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      float jx = 0.5f, jy = 0.5f;
      if (set == PointSet::Stratified) {
        jx = rng.nextFloat();
        jy = rng.nextFloat();
      }
      pts[size_t(j) * nx + i] =
          Vec2(std::min((i + jx) / nx, kOneMinusEpsilon), std::min((j + jy) / ny, kOneMinusEpsilon));
    }
  return pts;
}

std::vector<Vec3> warpedGridLines(WarpType type, float param, int lines, int segments) {
  return warpedGridLines(warpSampleFunction(type, param), lines, segments);
}

std::vector<Vec3> warpedGridLines(const SampleFunction& sample, int lines, int segments) {
  std::vector<Vec3> out;
  out.reserve(size_t(2) * (lines + 1) * segments * 2);
  auto at = [&](float a, float b, bool vertical) {
    a = std::min(a, kOneMinusEpsilon);
    b = std::min(b, kOneMinusEpsilon);
    return sample(vertical ? Vec2(a, b) : Vec2(b, a));
  };
  for (int dir = 0; dir < 2; ++dir)
    for (int l = 0; l <= lines; ++l) {
      float a = float(l) / lines;
      Vec3 prev = at(a, 0.f, dir == 0);
      for (int s = 1; s <= segments; ++s) {
        Vec3 next = at(a, float(s) / segments, dir == 0);
        if (prev != Vec3(0.f) && next != Vec3(0.f)) {
          out.push_back(prev);
          out.push_back(next);
        }
        prev = next;
      }
    }
  return out;
}

std::array<uint8_t, 3> sequentialColour(double t) {
  // Viridis, polynomial fit.
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
  static const double c[7][3] = {{0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
                                 {0.1050930431085774, 1.404613529898575, 1.384590162594685},
                                 {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
                                 {-4.634230498983486, -5.799100973351585, -19.33244095627987},
                                 {6.228269936347081, 14.17993336680509, 56.69055260068105},
                                 {4.776384997670288, -13.74514537774601, -65.35303263337234},
                                 {-5.435455855934631, 4.645852612178535, 26.3124352495832}};
  std::array<uint8_t, 3> rgb;
  for (int ch = 0; ch < 3; ++ch) {
    double v = c[6][ch];
    for (int i = 5; i >= 0; --i) v = c[i][ch] + t * v;
    rgb[ch] = static_cast<uint8_t>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
  }
  return rgb;
}

std::array<uint8_t, 3> divergingColour(double t) {
  t = std::clamp(std::isfinite(t) ? t : 0.0, -1.0, 1.0);
  const double mid[3] = {0.12, 0.12, 0.13}, neg[3] = {0.25, 0.55, 1.0}, pos[3] = {1.0, 0.55, 0.1};
  const double* end = t < 0 ? neg : pos;
  double a = std::fabs(t);
  std::array<uint8_t, 3> rgb;
  for (int ch = 0; ch < 3; ++ch)
    rgb[ch] = static_cast<uint8_t>(std::lround(255.0 * (mid[ch] + a * (end[ch] - mid[ch]))));
  return rgb;
}

HistogramPanels makeHistogramPanels(const Chi2Result& r) {
  HistogramPanels p;
  p.width = r.resX;
  p.height = r.resY;
  const size_t cells = size_t(r.resX) * r.resY;
  if (cells == 0 || r.observed.size() != cells || r.expected.size() != cells) return p;
  double mx = 0.0;
  for (size_t c = 0; c < cells; ++c) mx = std::max({mx, r.observed[c], r.expected[c]});
  p.scaleMax = mx > 0.0 ? mx : 1.0;
  p.observed.resize(cells * 4);
  p.expected.resize(cells * 4);
  p.difference.resize(cells * 4);
  const bool sphere = r.resX == 2 * r.resY;  // (phi, w) grids are twice as wide as high
  for (int y = 0; y < r.resY; ++y)
    for (int x = 0; x < r.resX; ++x) {
      // 2-D: y up (last row on top); sphere: w = 1 - cos(theta) = 0 on top.
      int row = sphere ? y : r.resY - 1 - y;
      size_t c = size_t(y) * r.resX + x, o = (size_t(row) * r.resX + x) * 4;
      auto put = [&](std::vector<uint8_t>& img, std::array<uint8_t, 3> rgb) {
        img[o] = rgb[0];
        img[o + 1] = rgb[1];
        img[o + 2] = rgb[2];
        img[o + 3] = 255;
      };
      put(p.observed, sequentialColour(r.observed[c] / p.scaleMax));
      put(p.expected, sequentialColour(r.expected[c] / p.scaleMax));
      put(p.difference, divergingColour((r.observed[c] - r.expected[c]) / p.scaleMax));
    }
  return p;
}

double meanAbsoluteDifference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  if (a.size() != b.size() || a.empty()) return 255.0;
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (i % 4 == 3) continue;
    sum += std::abs(int(a[i]) - int(b[i]));
    ++n;
  }
  return sum / double(n);
}

// ---- worker -----------------------------------------------------------------------------------------

WarpInspectorWorker::WarpInspectorWorker() : thread_([this] { run(); }) {}

WarpInspectorWorker::~WarpInspectorWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    ++generation_;  // cancels the job in progress
  }
  cv_.notify_all();
  thread_.join();
}

void WarpInspectorWorker::request(const WarpInspectorSettings& s) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (hasRequest_ && pending_ == s) return;
    pending_ = s;
    hasRequest_ = true;
    ++generation_;
  }
  cv_.notify_all();
}

std::shared_ptr<const WarpPoints> WarpInspectorWorker::points() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return points_;
}

std::shared_ptr<const WarpVerdict> WarpInspectorWorker::verdict() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return verdict_;
}

bool WarpInspectorWorker::idle() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return doneGeneration_ == generation_.load();
}

bool WarpInspectorWorker::waitIdle(double seconds) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return cv_.wait_for(lock, std::chrono::duration<double>(seconds),
                      [this] { return doneGeneration_ == generation_.load(); });
}

void WarpInspectorWorker::run() {
  for (;;) {
    WarpInspectorSettings s;
    uint64_t gen;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      cv_.wait(lock, [this] { return stop_ || (hasRequest_ && doneGeneration_ != generation_.load()); });
      if (stop_) return;
      s = pending_;
      gen = generation_.load();
    }
    auto check = [this, gen] {
      if (generation_.load(std::memory_order_relaxed) != gen) throw Cancelled{};
    };
    try {
      auto t0 = std::chrono::steady_clock::now();
      // 1. points (and grid lines), published first so the 3-D view follows the controls at once
      auto pts = std::make_shared<WarpPoints>();
      pts->settings = s;
      std::vector<Vec2> u = makePointSet(s);
      check();
      pts->points.resize(u.size());
      const SampleFunction sample = inspectorSample(s);
      for (size_t i = 0; i < u.size(); ++i) {
        if ((i & 0xffff) == 0) check();
        pts->points[i] = sample(u[i]);
      }
      if (s.gridLines) pts->lines = warpedGridLines(sample, 16, 64);
      {
        std::lock_guard<std::mutex> lock(mutex_);
        points_ = pts;
        ++publications_;
      }
      // 2. the chi-square test on the same points
      auto v = std::make_shared<WarpVerdict>();
      v->settings = s;
      v->domain = inspectorDomain(s);
      PdfFunction pdf = judgePdf(s);
      PdfFunction checkedPdf = [&](const Vec3& d) {
        check();
        return pdf(d);
      };
      Chi2Options opt;
      opt.resolution = inspectorResolution(s);
      opt.rejectedDraws = s.bsdf;
      v->chi2 = chi2TestPoints(v->domain, pts->points, checkedPdf, opt);
      v->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      {
        std::lock_guard<std::mutex> lock(mutex_);
        check();
        verdict_ = v;
        ++publications_;
        doneGeneration_ = gen;
      }
      cv_.notify_all();
    } catch (const Cancelled&) {
      ++cancelled_;
    }
  }
}

}  // namespace penumbra::ui
