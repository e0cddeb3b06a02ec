// The display's tone mapping on the CPU: a film snapshot (linear float RGB, plus its standard error)
// to RGBA8, pixel for pixel what shaders/display.frag computes. The colour view equals toSrgb8 of
// core/image/tonemap.cpp exactly (the PNG that `penumbra render` writes), because the table below is
// built from that very function.
//
// Why it exists: where GL is a software rasteriser (Mesa llvmpipe, the only GL on machines without a
// GPU) a per-pixel shader with a texture fetch and three pow() costs ~30 ns of CPU per pixel, taken
// from the render threads; this table-driven loop costs ~2 ns. ImageDisplay picks it on software GL
// and keeps display.frag on hardware GL. No GL here, so tests drive it directly.
#pragma once

#include <cstdint>
#include <vector>

#include "app/ui/viewer_controller.h"
#include "core/image/image.h"

namespace penumbra::ui {

// The 8-bit display level of a non-negative finite value t (after exposure) for one tone curve,
// exactly: levels change at 255 thresholds, and the table holds, for every group of 2^15 consecutive
// float bit patterns below 1.0, the level at the group's start and the one threshold inside it (the
// curves rise by less than half a level per group, so there is never more than one).
class DisplayLevelTable {
 public:
  explicit DisplayLevelTable(Tonemap curve);
  Tonemap curve() const { return curve_; }

  // Level of t >= 0 (finite, or +inf). Negative and NaN values must be handled by the caller.
  std::uint8_t operator()(float t) const {
    std::uint32_t b;
    static_assert(sizeof b == sizeof t);
    __builtin_memcpy(&b, &t, sizeof b);
    return levelOfBits(table_.data(), b);
  }
  // The same on the bit pattern of t, with the table's data() hoisted by the caller (hot loops).
  static std::uint32_t levelOfBits(const std::uint32_t* table, std::uint32_t b) {
    if (b >= kOne) return 255;
    std::uint32_t e = table[b >> kShift];
    return (e >> 16) + ((b & kLow) >= (e & 0xFFFFu));
  }
  const std::uint32_t* data() const { return table_.data(); }

  // The defining function: what the table reproduces, computed directly (slow; tests, construction).
  static std::uint8_t reference(Tonemap curve, float t);

 private:
  static constexpr std::uint32_t kOne = 0x3F800000u;  // bits of 1.0f: every curve gives 255 at and above
  static constexpr int kShift = 15;
  static constexpr std::uint32_t kLow = (1u << kShift) - 1;
  Tonemap curve_;
  // Per group: level at its start << 16 | low bits of the first value at the next level (0xFFFF: none).
  std::vector<std::uint32_t> table_;
};

// Byte order of the 4-byte pixels (the window system's order makes texture-to-window copies plain
// memory copies).
enum class PixelOrder { Rgba, Bgra };

// Tone maps `mean` (and `standardError` for the relative-error view; may be empty) into `pixels`
// (width * height pixels of 4 bytes in `order` in memory, alpha 255, image row 0 first), as
// shaders/display.frag does for `d.exposure`, `d.falseColour` and the table's curve.
// `table.curve()` must be `d.tonemap`.
void tonemapForDisplay(const Image& mean, const Image& standardError, const DisplaySettings& d,
                       const DisplayLevelTable& table, PixelOrder order, std::vector<std::uint32_t>& pixels);

// The colour view runs an AVX2 loop where the CPU has it (same results, bit for bit). For tests: whether
// it is in use, and a switch to the portable loop (enabling has no effect without AVX2).
bool displayTonemapSimd();
void setDisplayTonemapSimd(bool enabled);

}  // namespace penumbra::ui
