// Error of an estimate against a reference image.
//
// Every metric averages over pixels and the three colour channels:
//   MSE     = mean (v - ref)^2
//   relMSE  = mean (v - ref)^2 / (ref^2 + 0.01)
// When the reference carries its own per-pixel standard error s (a rendered reference), the
// estimate and the reference are independent, so E[(v - ref)^2] = E[(v - truth)^2] + s^2. The
// reported MSE subtracts mean(s^2) (and relMSE subtracts mean(s^2 / (ref^2 + 0.01))); it is then an
// unbiased estimate of the true MSE and can come out slightly negative once the estimate is as good as
// the reference. RMSE is sqrt(max(MSE, 0)).
//
// Uncertainty: per-pixel squared errors are independent across pixels (every pixel has its own
// random stream), so mseStdErr = stddev over pixels of the per-pixel squared error / sqrt(pixels).
//
// "No-light" pixels: a mask marks the pixels whose estimate can contain radiance of an emitter seen
// directly by the camera (see emitterMask in reference.h). Those pixels dominate squared errors
// (hundreds of times brighter than reflected light, and their filter-edge variance is the same for
// every light-sampling strategy), so every metric is also reported over the remaining pixels.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/image/image.h"

namespace penumbra {

struct ErrorStats {
  double mse = 0.0;          // reference noise subtracted when known
  double rmse = 0.0;         // sqrt(max(mse, 0))
  double relMse = 0.0;       // reference noise subtracted when known
  double mseStdErr = 0.0;    // standard error of `mse` itself
  double rawMse = 0.0;       // mean (v - ref)^2 before subtracting the reference's noise
  double refVariance = 0.0;  // mean s^2 of the reference (0 when unknown)
  std::size_t pixels = 0;
};

struct ErrorReport {
  ErrorStats all;      // every pixel
  ErrorStats noLight;  // pixels that see no emitter directly
};

// `refStdErr` may be empty (closed form or unknown); `seesLight` may be empty (no pixel excluded),
// else one entry per pixel, nonzero = excluded from noLight. Throws Error on size mismatch.
ErrorReport computeErrors(const Image& estimate, const Image& reference, const Image& refStdErr = {},
                          const std::vector<uint8_t>& seesLight = {});

// Least-squares slope of log(y) against log(x) over the points with x > 0 and y > 0 (NaN if < 2).
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace penumbra
