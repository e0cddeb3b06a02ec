// The warp inspector's state without GL: point sets, warped points and grid lines, the chi-square
// test (core/sampling/chi2) run on a background thread with cancellation of stale jobs, and the three
// histogram panels (observed, expected, signed difference) as RGBA8 images on one colour scale.
// app/ui/warp_inspector.* draws them; tests use this directly.
#pragma once

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/materials/bsdf_warp.h"
#include "core/sampling/chi2.h"
#include "core/sampling/sampler.h"
#include "core/sampling/warp.h"
#include "core/sampling/warp_params.h"

namespace penumbra::ui {

// Sampler: the first 2^k samples of one request (dimension pair) of a render sampler at one pixel.
enum class PointSet : uint8_t { Independent, Grid, Stratified, Sampler };
inline constexpr int kPointSetCount = 4;
const char* pointSetName(PointSet s);  // independent, grid, stratified, sampler
bool parsePointSet(const std::string& name, PointSet& out);

using penumbra::kMaxLog2Points;
using penumbra::kMinLog2Points;

struct WarpInspectorSettings {
  WarpType type = WarpType::CosineHemisphere;
  float param = 0.5f;  // uniform-cone: cos(theta_max); beckmann: alpha (ignored by the others)
  int log2Points = 14;
  PointSet pointSet = PointSet::Independent;
  bool mismatch = false;  // judge the samples by a deliberately wrong pdf
  bool gridLines = false;
  uint64_t seed = 1;
  int resolution = 0;  // chi-square grid (0: chosen from the point count)
  // PointSet::Sampler: which sampler, which of its 2-D requests (0: the pixel filter's), which pixel.
  SamplerKind sampler = SamplerKind::Sobol;
  int request = 0;
  int pixelX = 0, pixelY = 0;
  // A BSDF's sampling instead of the warp `type` (core/materials/bsdf_warp.h): its lobe from wo at
  // `incidentDegrees`, rejected draws (below the surface) at the origin and tested as a cell of their
  // own. `type` and `param` are kept for going back to the warp.
  bool bsdf = false;
  BsdfType bsdfType = BsdfType::Microfacet;                                // Microfacet or RoughConductor
  MicrofacetDistribution distribution = MicrofacetDistribution::Beckmann;  // roughconductor
  float alpha = 0.1f, kd = 0.5f, incidentDegrees = 30.f;
  float intIOR = 1.5046f, extIOR = 1.000277f;  // microfacet
  bool operator==(const WarpInspectorSettings&) const = default;
};

// The BSDF warp the settings describe (their values were checked when entered).
BsdfWarp bsdfWarpOf(const WarpInspectorSettings& s);
// The values as `penumbra warp microfacet|roughconductor` takes them.
BsdfWarpInputs bsdfInputsOf(const WarpInspectorSettings& s);
// Takes checked BSDF inputs (checkedBsdfWarp: the CLI's code and messages) into the settings; a value
// the CLI refuses leaves them as they were and returns its message ("" when taken).
std::string enterBsdf(WarpInspectorSettings& s, const BsdfWarpInputs& in);
// Whether the samples lie on the sphere (spherical warps and BSDFs), what draws them, and the χ²
// domain they are binned in.
bool showsSphere(const WarpInspectorSettings& s);
SampleFunction inspectorSample(const WarpInspectorSettings& s);
Chi2Domain inspectorDomain(const WarpInspectorSettings& s);
// A name for the panel's title: the warp's, or "roughconductor ggx alpha 0.1 at 30 deg".
std::string inspectedName(const WarpInspectorSettings& s);

using penumbra::defaultWarpParam;  // uniform-cone 0.5, beckmann 0.2

// Values entered in the inspector's controls, checked as `penumbra warp` checks --param, --points,
// --request and --pixel (core/sampling/warp_params.h, the same code and messages): a value the CLI
// refuses leaves the settings as they were and returns the CLI's message ("" when taken).
std::string enterWarpParam(WarpInspectorSettings& s, double value);
std::string enterLog2Points(WarpInspectorSettings& s, int64_t log2Points);
std::string enterSamplerRequest(WarpInspectorSettings& s, int64_t request);
std::string enterSamplerPixel(WarpInspectorSettings& s, int64_t x, int64_t y);
// The histogram resolution used (2-D: res x res cells; sphere: 2 res x res in (phi, cos theta)).
int inspectorResolution(const WarpInspectorSettings& s);
// What the samples are judged by ("the warp's own pdf" or the mismatched one, in words).
std::string judgeDescription(const WarpInspectorSettings& s);
// The pdf that judges the samples: the warp's own, or with `mismatch` a wrong one for the same
// domain (the uniform density of the warp's square or cap; for warps that are uniform already, the
// cosine-weighted hemisphere, the tent, a narrower cone or a rougher Beckmann).
PdfFunction judgePdf(const WarpInspectorSettings& s);

// 2^log2 points of [0,1)^2. Independent: the PCG stream of chi2Test for `seed` (so the inspector's
// samples are the CLI's); grid: cell centres of a 2^ceil(k/2) x 2^floor(k/2) grid, row by row;
// stratified: one jittered point per cell of that grid.
std::vector<Vec2> makePointSet(PointSet set, int log2Points, uint64_t seed);
// The first 2^log2 samples (sample indices 0, 1, ...) of 2-D request `request` of `sampler` at
// `pixel`, the sampler set up for a run of 2^log2 samples per pixel.
std::vector<Vec2> makeSamplerPointSet(SamplerKind sampler, int log2Points, uint64_t seed, int request,
                                      IVec2 pixel);
// Either of the above, as the settings ask.
std::vector<Vec2> makePointSet(const WarpInspectorSettings& s);
// Warped lines of the unit square (`lines` + 1 per direction, each cut into `segments` pieces) as
// GL_LINES endpoint pairs.
std::vector<Vec3> warpedGridLines(WarpType type, float param, int lines, int segments);
// The same for any sample function; segments with a rejected end (the zero vector) are left out.
std::vector<Vec3> warpedGridLines(const SampleFunction& sample, int lines, int segments);

struct WarpPoints {
  WarpInspectorSettings settings;
  std::vector<Vec3> points;  // in sample-index order
  std::vector<Vec3> lines;   // GL_LINES pairs (empty without grid lines)
};

struct WarpVerdict {
  WarpInspectorSettings settings;
  Chi2Domain domain;
  Chi2Result chi2;
  double seconds = 0.0;
};

// The panels drawn side by side, row 0 at the top: 2-D warps with y up, spherical ones with
// cos(theta) = 1 at the top and phi from 0 (left) to 2 pi. Counts per cell on one scale [0, scaleMax]
// (viridis); the difference observed - expected on [-scaleMax, scaleMax] (blue - dark - orange).
struct HistogramPanels {
  int width = 0, height = 0;
  double scaleMax = 1.0;
  std::vector<uint8_t> observed, expected, difference;  // RGBA8
};
HistogramPanels makeHistogramPanels(const Chi2Result& r);
std::array<uint8_t, 3> sequentialColour(double t);  // t in [0, 1]
std::array<uint8_t, 3> divergingColour(double t);   // t in [-1, 1]
// Mean absolute difference of two RGBA8 images' RGB bytes (0 ... 255).
double meanAbsoluteDifference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

// One background thread computing points, then the verdict, for the latest requested settings. A new
// request cancels the job in progress (checked while warping and inside every pdf evaluation of the
// quadrature), so dragging a slider at 2^20 points never queues stale work.
class WarpInspectorWorker {
 public:
  WarpInspectorWorker();
  ~WarpInspectorWorker();
  WarpInspectorWorker(const WarpInspectorWorker&) = delete;
  WarpInspectorWorker& operator=(const WarpInspectorWorker&) = delete;

  // Starts computing for `s` unless it is the last request already.
  void request(const WarpInspectorSettings& s);
  // The newest published results (may belong to older settings while a job runs).
  std::shared_ptr<const WarpPoints> points() const;
  std::shared_ptr<const WarpVerdict> verdict() const;
  // Incremented on every publication: cheap change detection for the UI.
  uint64_t publications() const { return publications_.load(); }
  // True when the points and the verdict of the last request are published.
  bool idle() const;
  // Waits until idle() or the timeout; returns idle().
  bool waitIdle(double seconds) const;
  uint64_t cancelledJobs() const { return cancelled_.load(); }

 private:
  void run();

  mutable std::mutex mutex_;
  mutable std::condition_variable cv_;
  WarpInspectorSettings pending_;
  bool hasRequest_ = false, stop_ = false;
  std::atomic<uint64_t> generation_{0};
  uint64_t doneGeneration_ = 0;
  std::atomic<uint64_t> publications_{0}, cancelled_{0};
  std::shared_ptr<const WarpPoints> points_;
  std::shared_ptr<const WarpVerdict> verdict_;
  std::thread thread_;
};

}  // namespace penumbra::ui
