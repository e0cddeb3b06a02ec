#include "app/ui/display_tonemap.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include "app/ui/light_share_map.h"

#include <immintrin.h>

#include "core/image/tonemap.h"
#include "core/math/error.h"

namespace penumbra::ui {

namespace {

float fromBits(std::uint32_t b) {
  float t;
  std::memcpy(&t, &b, sizeof t);
  return t;
}

// Blue → cyan → green → yellow → red, as display.frag's ramp(); `out` in the order of `o`.
void ramp(float t, std::uint8_t* out, PixelOrder o) {
  t = std::clamp(t, 0.f, 1.f) * 4.f;
  float r, g, b;
  if (t < 1.f)
    r = 0.f, g = t, b = 1.f;
  else if (t < 2.f)
    r = 0.f, g = 1.f, b = 2.f - t;
  else if (t < 3.f)
    r = t - 2.f, g = 1.f, b = 0.f;
  else
    r = 1.f, g = 4.f - t, b = 0.f;
  const bool bgra = o == PixelOrder::Bgra;
  out[bgra ? 2 : 0] = std::uint8_t(r * 255.f + 0.5f);
  out[1] = std::uint8_t(g * 255.f + 0.5f);
  out[bgra ? 0 : 2] = std::uint8_t(b * 255.f + 0.5f);
  out[3] = 255;
}

float luminance(const float* c) {
  return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
}

// The colour view for n pixels, one 32-bit store per pixel. NaN and Inf inputs (exponent all ones)
// give 0, as do negative and zero exposed values; a value the exposure pushed past FLT_MAX is +inf,
// which the table maps to 255, as display() does.
void colourScalar(const float* m, std::size_t n, float scale, const std::uint32_t* tab, PixelOrder o,
                  std::uint32_t* out) {
  const int rShift = o == PixelOrder::Bgra ? 16 : 0, bShift = 16 - rShift;
  auto channel = [tab, scale](float v) -> std::uint32_t {
    std::uint32_t b;
    std::memcpy(&b, &v, sizeof b);
    if ((b & 0x7F800000u) == 0x7F800000u) return 0;
    float t = v * scale;
    std::memcpy(&b, &t, sizeof b);
    return (b >> 31) ? 0 : DisplayLevelTable::levelOfBits(tab, b);
  };
  for (std::size_t i = 0; i < n; ++i, m += 3)
    out[i] = channel(m[0]) << rShift | channel(m[1]) << 8 | channel(m[2]) << bShift | 0xFF000000u;
}

bool haveAvx2() {
  return __builtin_cpu_supports("avx2");
}

// Levels of 4 channel values (colourScalar's channel(), lane by lane).
__attribute__((target("avx2"))) inline __m128i levelsAvx2(__m128 v, __m128 scale, const std::uint32_t* tab) {
  const __m128i expMask = _mm_set1_epi32(0x7F800000);
  __m128i b = _mm_castps_si128(v);
  __m128i bad = _mm_cmpeq_epi32(_mm_and_si128(b, expMask), expMask);  // NaN or Inf input: 0
  __m128i t = _mm_castps_si128(_mm_mul_ps(v, scale));
  bad = _mm_or_si128(bad, _mm_srai_epi32(t, 31));                // negative (or -0) exposed: 0
  __m128i big = _mm_cmpgt_epi32(t, _mm_set1_epi32(0x3F7FFFFF));  // >= 1 (or +inf): 255
  __m128i idx = _mm_min_epu32(_mm_srli_epi32(t, 15), _mm_set1_epi32((0x3F800000 >> 15) - 1));
  __m128i e = _mm_i32gather_epi32(reinterpret_cast<const int*>(tab), idx, 4);
  __m128i below = _mm_cmpgt_epi32(_mm_and_si128(e, _mm_set1_epi32(0xFFFF)),  // -1 below the threshold
                                  _mm_and_si128(t, _mm_set1_epi32(0x7FFF)));
  __m128i level = _mm_add_epi32(_mm_add_epi32(_mm_srli_epi32(e, 16), _mm_set1_epi32(1)), below);
  level = _mm_blendv_epi8(level, _mm_set1_epi32(255), big);
  return _mm_andnot_si128(bad, level);
}

// colourScalar 4 pixels (12 channels) at a time, with AVX2 gathers from the table; returns the number
// of pixels done (a multiple of 4). Same results, bit for bit.
__attribute__((target("avx2"))) std::size_t colourAvx2(const float* m, std::size_t n, float scale,
                                                       const std::uint32_t* tab, PixelOrder o,
                                                       std::uint32_t* out) {
  const __m128 vscale = _mm_set1_ps(scale);
  // 12 levels r0 g0 b0 r1 .. b3 as bytes 0..11 → four RGBA (or BGRA) pixels, alpha 255.
  const __m128i spread = o == PixelOrder::Bgra
                             ? _mm_setr_epi8(2, 1, 0, -1, 5, 4, 3, -1, 8, 7, 6, -1, 11, 10, 9, -1)
                             : _mm_setr_epi8(0, 1, 2, -1, 3, 4, 5, -1, 6, 7, 8, -1, 9, 10, 11, -1);
  const __m128i alpha = _mm_set1_epi32(int(0xFF000000u));
  const std::size_t groups = n / 4;
  for (std::size_t g = 0; g < groups; ++g, m += 12) {
    __m128i a = levelsAvx2(_mm_loadu_ps(m), vscale, tab), b = levelsAvx2(_mm_loadu_ps(m + 4), vscale, tab),
            c = levelsAvx2(_mm_loadu_ps(m + 8), vscale, tab);
    __m128i bytes = _mm_packus_epi16(_mm_packus_epi32(a, b), _mm_packus_epi32(c, c));
    __m128i px = _mm_or_si128(_mm_shuffle_epi8(bytes, spread), alpha);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 4 * g), px);
  }
  return groups * 4;
}

bool gSimd = haveAvx2();

}  // namespace

std::uint8_t DisplayLevelTable::reference(Tonemap curve, float t) {
  if (curve == Tonemap::Srgb) return toSrgb8(t);
  if (!std::isfinite(t)) return 0;
  float v = std::clamp(std::pow(std::max(t, 0.f), 1.f / 2.2f), 0.f, 1.f);
  return std::uint8_t(v * 255.f + 0.5f);
}

DisplayLevelTable::DisplayLevelTable(Tonemap curve) : curve_(curve) {
  const std::uint32_t groups = kOne >> kShift;
  table_.resize(groups);
  for (std::uint32_t i = 0; i < groups; ++i) {
    std::uint32_t lo = i << kShift, hi = ((i + 1) << kShift) - 1;
    std::uint8_t a = reference(curve, fromBits(lo)), b = reference(curve, fromBits(hi));
    table_[i] = std::uint32_t(a) << 16 | 0xFFFFu;
    if (a == b) continue;
    if (b != a + 1) throw Error("display level table: more than one level change in a group");
    while (lo + 1 < hi) {  // invariant: level(lo) == a, level(hi) == a + 1
      std::uint32_t mid = lo + (hi - lo) / 2;
      (reference(curve, fromBits(mid)) == a ? lo : hi) = mid;
    }
    table_[i] = std::uint32_t(a) << 16 | (hi & kLow);
  }
}

void tonemapForDisplay(const Image& mean, const Image& standardError, const DisplaySettings& d,
                       const DisplayLevelTable& table, PixelOrder order, std::vector<std::uint32_t>& pixels) {
  const int ri = order == PixelOrder::Bgra ? 2 : 0, bi = 2 - ri;  // byte of red, of blue
  const std::size_t n = std::size_t(mean.width) * std::size_t(mean.height);
  pixels.resize(n);
  const float scale = std::exp2(d.exposure);
  // display() of display.frag for one channel.
  auto level = [&](float linear) -> std::uint8_t {
    if (!std::isfinite(linear)) return 0;
    float t = linear * scale;
    if (std::isinf(t)) return t > 0.f ? 255 : 0;
    return t > 0.f ? table(t) : 0;
  };
  const float* m = mean.rgb.data();
  std::uint8_t* o = reinterpret_cast<std::uint8_t*>(pixels.data());

  if (d.falseColour == FalseColour::RelativeError) {
    // Relative standard error of the luminance, log scale: 0.1 % (blue) … 100 % (red); black: no data.
    bool haveError = standardError.width == mean.width && standardError.height == mean.height;
    const float* e = standardError.rgb.data();
    for (std::size_t i = 0; i < n; ++i, m += 3, o += 4) {
      float lm = luminance(m);
      if (!haveError || !(lm > 0.f)) {
        o[0] = o[1] = o[2] = 0, o[3] = 255;
        continue;
      }
      float r = luminance(e + 3 * i) / lm;
      ramp((std::log10(std::max(r, 1e-3f)) + 3.f) / 3.f, o, order);
    }
    return;
  }
  if (d.falseColour == FalseColour::MisLightShare) {
    // A light-share film: the light technique's share of each pixel's area-light estimate.
    for (std::size_t i = 0; i < n; ++i, m += 3, o += 4) {
      std::uint8_t rgb[3];
      lightShareRgb(lightShare(Color3(m[0], m[1], m[2])), rgb);
      o[ri] = rgb[0], o[1] = rgb[1], o[bi] = rgb[2], o[3] = 255;
    }
    return;
  }
  if (d.falseColour == FalseColour::BadPixels) {
    // Magenta: NaN/Inf; cyan: negative; otherwise the displayed luminance, dimmed.
    for (std::size_t i = 0; i < n; ++i, m += 3, o += 4) {
      bool nonFinite = !std::isfinite(m[0]) || !std::isfinite(m[1]) || !std::isfinite(m[2]);
      bool negative = m[0] < 0.f || m[1] < 0.f || m[2] < 0.f;
      o[3] = 255;
      if (nonFinite) {
        o[ri] = 255, o[1] = 0, o[bi] = 255;
      } else if (negative) {
        o[ri] = 0, o[1] = 255, o[bi] = 255;
      } else {
        float c[3] = {level(m[0]) / 255.f, level(m[1]) / 255.f, level(m[2]) / 255.f};
        o[0] = o[1] = o[2] = std::uint8_t(luminance(c) * 0.6f * 255.f + 0.5f);
      }
    }
    return;
  }
  // The colour view.
  const std::uint32_t* tab = table.data();
  std::uint32_t* out = pixels.data();  // 4 bytes in memory order: little-endian
  std::size_t done = gSimd ? colourAvx2(m, n, scale, tab, order, out) : 0;
  colourScalar(m + 3 * done, n - done, scale, tab, order, out + done);
}

bool displayTonemapSimd() {
  return gSimd;
}

void setDisplayTonemapSimd(bool enabled) {
  gSimd = enabled && haveAvx2();
}

}  // namespace penumbra::ui
