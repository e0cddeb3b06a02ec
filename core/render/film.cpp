#include "core/render/film.h"

#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/math/error.h"

namespace penumbra {

namespace {

// Zeroing a fresh 768² film (28 MB) faults in 7,000 small pages, ~75 ms on a virtual machine; in
// 2 MB pages it takes a fraction of that. Only advice: the kernel may decline, nothing changes.
void adviseHugePages(const double* data, size_t count) {
  if (count * sizeof(double) < (size_t(4) << 20)) return;
  const uintptr_t begin = reinterpret_cast<uintptr_t>(data) & ~uintptr_t(4095);
  const uintptr_t end = reinterpret_cast<uintptr_t>(data + count);
  ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

}  // namespace

void Film::reset(int width, int height) {
  width_ = width;
  height_ = height;
  const size_t count = size_t(width) * height * 6;
  if (sums_.capacity() < count) {
    std::vector<double>().swap(sums_);  // the old film's memory goes back before the new one is taken
    sums_.reserve(count);
    adviseHugePages(sums_.data(), count);
  }
  sums_.assign(count, 0.0);
}

Film::Film(int width, int height, std::vector<double> sums)
    : width_(width), height_(height), sums_(std::move(sums)) {
  if (sums_.size() != size_t(std::max(width, 0)) * size_t(std::max(height, 0)) * 6)
    throw Error("film sums of " + std::to_string(sums_.size()) + " values for " + std::to_string(width) +
                "x" + std::to_string(height) + " pixels");
}

void Film::clear() {
  std::fill(sums_.begin(), sums_.end(), 0.0);
}

void Film::resolveMeanRow(uint32_t spp, Image& out, int y) const {
  const double inv = spp > 0 ? 1.0 / spp : 0.0;
  for (int x = 0; x < width_; ++x) {
    size_t i = size_t(y) * width_ + x;
    const double* s = &sums_[i * 6];
    float* o = &out.rgb[i * 3];
    for (int c = 0; c < 3; ++c) o[c] = float(s[c] * inv);
  }
}

void Film::resolveMean(uint32_t spp, Image& out, int y0, int y1) const {
  for (int y = y0; y < y1; ++y) resolveMeanRow(spp, out, y);
}

void Film::resolveMean(const std::vector<uint32_t>& rowSpp, Image& out, int y0, int y1) const {
  for (int y = y0; y < y1; ++y) resolveMeanRow(rowSpp[size_t(y)], out, y);
}

Image Film::mean(uint32_t spp) const {
  Image img(width_, height_);
  resolveMean(spp, img, 0, height_);
  return img;
}

namespace {

// Standard error of the mean of n samples with sum s and sum of squares s2 (0 below 2 samples).
float standardErrorOf(double s, double s2, uint32_t spp) {
  if (spp < 2) return 0.f;
  double n = spp, m = s / n;
  // Unbiased sample variance of the samples, then of their mean.
  double var = std::max(0.0, (s2 - n * m * m) / (n - 1.0));
  return float(std::sqrt(var / n));
}

}  // namespace

void Film::resolveStandardErrorRow(uint32_t spp, Image& out, int y) const {
  for (int x = 0; x < width_; ++x) {
    size_t i = size_t(y) * width_ + x;
    const double* s = &sums_[i * 6];
    float* o = &out.rgb[i * 3];
    for (int c = 0; c < 3; ++c) o[c] = standardErrorOf(s[c], s[c + 3], spp);
  }
}

void Film::resolveStandardError(uint32_t spp, Image& out, int y0, int y1) const {
  for (int y = y0; y < y1; ++y) resolveStandardErrorRow(spp, out, y);
}

void Film::resolveStandardError(const std::vector<uint32_t>& rowSpp, Image& out, int y0, int y1) const {
  for (int y = y0; y < y1; ++y) resolveStandardErrorRow(rowSpp[size_t(y)], out, y);
}

void Film::pixelStatistics(uint32_t spp, int x, int y, Color3& mean, Color3& standardError) const {
  const double* s = &sums_[(size_t(y) * width_ + x) * 6];
  const double inv = spp > 0 ? 1.0 / spp : 0.0;
  for (int c = 0; c < 3; ++c) {
    mean[c] = float(s[c] * inv);
    standardError[c] = standardErrorOf(s[c], s[c + 3], spp);
  }
}

Image Film::standardError(uint32_t spp) const {
  Image img(width_, height_);
  resolveStandardError(spp, img, 0, height_);
  return img;
}

}  // namespace penumbra
