// Accumulation buffer: per-pixel double sums of the sample values and of their squares, so the
// viewer and the analysis can show the mean and its standard error. Samples are added one pass at a
// time by whichever worker owns the pixel's row in that pass; no locks are needed.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image/image.h"
#include "core/math/vec.h"

namespace penumbra {

class Film {
 public:
  Film() = default;
  Film(int width, int height) { reset(width, height); }
  // A film holding `sums` (width * height * 6 values, as sums() gives them; e.g. the total of
  // processes that shared a render), taken without a copy.
  Film(int width, int height, std::vector<double> sums);

  void reset(int width, int height);
  void clear();

  // Adds one weighted sample to a pixel (the caller has already rejected non-finite values).
  [[gnu::always_inline]] void add(int x, int y, const Color3& value) {  // once per camera sample
    double* s = sumsAt(x, y);
    s[0] += value.x;
    s[1] += value.y;
    s[2] += value.z;
    s[3] += double(value.x) * value.x;
    s[4] += double(value.y) * value.y;
    s[5] += double(value.z) * value.z;
  }

  // The sums of pixel (x, y), followed by those of the rest of its row and the rows below.
  double* sumsAt(int x, int y) { return &sums_[(size_t(y) * width_ + x) * 6]; }

  // The raw sums, 6 doubles per pixel in row order (r, g, b, r^2, g^2, b^2): what processes that
  // share a render add up.
  const std::vector<double>& sums() const { return sums_; }
  std::vector<double>& sums() { return sums_; }

  int width() const { return width_; }
  int height() const { return height_; }

  // Mean of `spp` samples per pixel, for rows [y0, y1).
  void resolveMean(uint32_t spp, Image& out, int y0, int y1) const;
  // The same with rowSpp[y] samples in each pixel of row y (a render stopped inside a pass).
  void resolveMean(const std::vector<uint32_t>& rowSpp, Image& out, int y0, int y1) const;
  Image mean(uint32_t spp) const;
  // Standard error of the mean (per channel) for rows [y0, y1); zero below 2 samples.
  void resolveStandardError(uint32_t spp, Image& out, int y0, int y1) const;
  void resolveStandardError(const std::vector<uint32_t>& rowSpp, Image& out, int y0, int y1) const;
  Image standardError(uint32_t spp) const;
  // Mean and standard error of one pixel (as resolveMean / resolveStandardError would give them).
  void pixelStatistics(uint32_t spp, int x, int y, Color3& mean, Color3& standardError) const;

 private:
  void resolveMeanRow(uint32_t spp, Image& out, int y) const;
  void resolveStandardErrorRow(uint32_t spp, Image& out, int y) const;

  int width_ = 0, height_ = 0;
  std::vector<double> sums_;  // per pixel: sum r, g, b, sum r^2, g^2, b^2
};

}  // namespace penumbra
