// The sample streams of the `sobol` and `zsobol` samplers: Owen-scrambled Sobol' points with the
// index shuffled per request (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4);
// pbrt-v4's padded Sobol' and ZSobol samplers). The two differ only in how a pixel sample picks
// its sequence index and seeds (its start); every next1D/next2D is the same code.
//
// `sobol`: per pixel its own sequence (indices = sample indices), every shuffle and scramble seeded
// from (seed, pixel, request), so pixels are independent.
//
// `zsobol`: one sequence per tile of pixels, pixel p taking the indices of its Morton code (Ahmed
// and Wonka 2020, "Screen-space blue-noise diffusion of Monte Carlo sampling error via hierarchical
// ordering of pixels"; pbrt-v4's ZSobolSampler). With 2^m = the run's sample count rounded up to a
// power of two, pixel p's first 2^m samples are the indices (morton(p) << m) + [0, 2^m), shuffled
// by a nested uniform scramble that maps every aligned 2^j x 2^j pixel tile onto one aligned block
// of the sequence: at 2^m samples every tile's samples together form a (0, m + 2j, 2)-net, so the
// errors of neighbouring pixels cancel (their error is spread like blue noise). Ahmed and Wonka
// permute base-4 digits; this base-2 scramble also maps tiles onto blocks and costs one hash
// instead of one per digit. For sample indices s >= 2^m the shuffled index is XORed with s's bits
// above m, so each pixel keeps getting nets (its first 2^k indices stay one aligned block), but
// neighbours no longer share one: the error is blue noise at 2^m samples per pixel.
//
// Both are progressive: for every k, the first 2^k samples of a pixel form a (0,2)-net in every
// 2-D request and a (0,1)-net in every 1-D request, whatever the final count. A stream is a pure
// function of (seed, pixel, sample index).
//
// Limits: any number of requests (each pads with its own shuffle of dimensions 0 and 1, so no
// request needs a dimension past the table); 32-bit sample indices; 24-bit values
// (bitsToUnitFloat), so nets of up to 2^24 points are exact. zsobol: the index has 32 bits, so
// only the Morton code's lowest kZSobolTileBits are in it and the bits above choose the seeds (tiles
// of 64 x 64 pixels are randomised independently of each other); m <= kZSobolMaxLog2Samples.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "core/math/vec.h"
#include "core/sampling/morton.h"
#include "core/sampling/owen_scramble.h"
#include "core/sampling/rng.h"
#include "core/sampling/sobol_points.h"

namespace penumbra {

// zsobol keeps 12 bits of the Morton code in the index: tiles of 64 x 64 pixels share one
// sequence, and up to 2^20 samples (times array points) per pixel fit beside them.
inline constexpr uint32_t kZSobolTileBits = 12;
inline constexpr uint32_t kZSobolMaxLog2Samples = 32 - kZSobolTileBits;
inline constexpr uint32_t kZSobolTileSideBits = kZSobolTileBits / 2;  // 64 pixels
static_assert(kZSobolTileBits % 2 == 0);

// reverseBits32(spreadBitsToEven(v)) for v < 2^kZSobolTileSideBits: the bit-reversed Morton code
// of a pixel within its tile is kZSobolReversedSpread[x] | kZSobolReversedSpread[y] >> 1.
inline constexpr auto kZSobolReversedSpread = [] {
  std::array<uint32_t, 1u << kZSobolTileSideBits> t{};
  for (uint32_t v = 0; v < t.size(); ++v)
    for (uint32_t i = 0; i < kZSobolTileSideBits; ++i)
      if (v >> i & 1) t[v] |= 1u << (31 - 2 * i);
  return t;
}();

// ceil(log2(n)), at most kZSobolMaxLog2Samples: m for zsobol from the run's sample count.
inline uint32_t zsobolLog2Samples(uint32_t sampleCount) {
  return std::min<uint32_t>(std::bit_width(std::max<uint32_t>(sampleCount, 1) - 1), kZSobolMaxLog2Samples);
}

// zsobol: the word the streams of the tile holding pixel (x, y) combine with the seed's hash: the
// Morton code's bits above the tile, i.e. the Morton code of the tile's coordinates.
inline uint64_t zsobolTileWord(uint32_t x, uint32_t y) {
  return encodeMorton2(x >> kZSobolTileSideBits, y >> kZSobolTileSideBits);
}
// zsobol: the key of the streams of the tile holding pixel (x, y).
inline uint64_t zsobolTileKey(uint64_t seedHash, uint32_t x, uint32_t y) {
  return hashCombine(seedHash, zsobolTileWord(x, y));
}

// zsobol: the Morton code of pixel (x, y) within its tile, bit-reversed.
inline uint32_t zsobolReversedTileCode(uint32_t x, uint32_t y) {
  constexpr uint32_t side = (1u << kZSobolTileSideBits) - 1;
  return kZSobolReversedSpread[x & side] | kZSobolReversedSpread[y & side] >> 1;
}

// zsobol: the top m bits of a bit-reversed index, where the sample index s mod 2^m sits; the index of
// (tile, sample) is the tile code shifted right by m with these bits of reversed s, and s's other
// bits are XORed in after the shuffle.
inline constexpr uint32_t zsobolSampleBits(uint32_t m) {
  return ~(~0u >> m);
}

template <class Randomizer>
class BasicSobolStream {
 public:
  // seedHash: mix64(seed). One hash; the sample index's bit reversal is kept while the index repeats
  // (the renderer restarts every pixel of a pass with one index).
  void startSobol(uint64_t seedHash, IVec2 pixel, uint32_t sampleIndex) {
    key_ = pixelStreamKey(seedHash, static_cast<uint32_t>(pixel.x), static_cast<uint32_t>(pixel.y));
    zsobol_ = false;
    sampleIndex_ = sampleIndex;
    reversedIndex_ = reversedSampleIndex(sampleIndex);
    reversedIndexXor_ = 0;
    request_ = 0;
    prepare();
  }

  // log2Samples: zsobolLog2Samples(the run's sample count). The tile's hash is kept while the pixel
  // stays in its tile, and the sample index's bit reversal while the index repeats.
  void startZSobol(uint64_t seedHash, uint32_t log2Samples, IVec2 pixel, uint32_t sampleIndex) {
    const auto x = static_cast<uint32_t>(pixel.x), y = static_cast<uint32_t>(pixel.y);
    const uint64_t tile =
        (static_cast<uint64_t>(x >> kZSobolTileSideBits) << 32) | (y >> kZSobolTileSideBits);
    if (tile != memoTile_ || seedHash != memoSeedHash_) {
      memoTile_ = tile;
      memoSeedHash_ = seedHash;
      memoTileKey_ = zsobolTileKey(seedHash, x, y);
    }
    key_ = memoTileKey_;
    zsobol_ = true;
    reversedTileCode_ = zsobolReversedTileCode(x, y);
    log2Samples_ = log2Samples;
    sampleIndex_ = sampleIndex;
    setZSobolIndex(log2Samples, reversedSampleIndex(sampleIndex), reversedIndex_, reversedIndexXor_);
    request_ = 0;
    prepare();
  }

  // Uniform in [0, 1): never returns 1.0.
  float next1D() {
    const float v = sobolPoint1D<Randomizer>(index_, hash_);
    advance();
    return v;
  }
  Vec2 next2D() {
    const Vec2 v = sobolPoint2D<Randomizer>(index_, hash_);
    advance();
    return v;
  }

  // Point j of n (j = 0 .. n - 1, in order) of one request: the points of sequence indices
  // sampleIndex * n + j, so a pixel sample's n points are stratified among themselves (a net when n
  // is a power of two) and all of a pixel's first 2^k samples together too. The request advances
  // after point n - 1. For zsobol the array's index takes ceil(log2 n) more bits.
  Vec2 next2D(uint32_t j, uint32_t n) {
    // n = 1: index sampleIndex, zsobol's m unchanged (m + 0 <= kZSobolMaxLog2Samples): a plain request.
    if (n == 1) return next2D();
    const uint64_t h = hash_;
    if (j + 1 >= n) advance();
    const uint32_t index = sampleIndex_ * n + j;
    uint32_t reversed, reversedXor = 0;
    if (zsobol_)
      setZSobolIndex(std::min(log2Samples_ + zsobolLog2Samples(n), kZSobolMaxLog2Samples),
                     reverseBits32(index), reversed, reversedXor);
    else
      reversed = reverseBits32(index);
    return sobolPoint2D<Randomizer>(shuffled(reversed, reversedXor, h), h);
  }

  // Point j of n of the k-th of m array requests drawn interleaved (shading sample j draws its m
  // values, k = 0 .. m - 1, before sample j + 1 draws its): the points that m array requests drawn
  // one after another would give, so each of the m is stratified over the n samples. The m
  // requests advance together after point n - 1 of request m - 1.
  // The prepared request is moved only when it is not already the one drawn or the one next.
  Vec2 next2D(uint32_t j, uint32_t n, uint32_t k, uint32_t m) {
    const uint32_t first = request_;
    if (k != 0) {
      request_ = first + k;
      prepare();
    }
    const Vec2 v = next2D(j, n);
    const uint32_t next = j + 1 >= n && k + 1 >= m ? first + m : first;
    if (request_ != next) {
      request_ = next;
      prepare();
    }
    return v;
  }

 private:
  // The next request's hash and shuffled index are computed one request ahead, so they are ready
  // (off the critical path of the sample that needs them) when it is drawn.
  void prepare() {
    hash_ = requestHash(key_, request_);
    index_ = shuffled(reversedIndex_, reversedIndexXor_, hash_);
  }
  void advance() {
    ++request_;
    prepare();
  }

  static uint32_t shuffled(uint32_t reversedIndex, uint32_t reversedXor, uint64_t requestHash) {
    return Randomizer::shuffledReversedIndex(reversedIndex, static_cast<uint32_t>(requestHash)) ^ reversedXor;
  }

  // zsobol's index of (tile, sample): (tileCode << m) | (s mod 2^m); s's bits above m are XORed in
  // after the shuffle. Both from s bit-reversed: s mod 2^m is its top m bits.
  void setZSobolIndex(uint32_t m, uint32_t reversedS, uint32_t& reversed, uint32_t& reversedXor) const {
    const uint32_t top = zsobolSampleBits(m);
    reversed = (reversedTileCode_ >> m) | (reversedS & top);
    reversedXor = reversedS & ~top;
  }

  uint32_t reversedSampleIndex(uint32_t sampleIndex) {
    if (sampleIndex != memoIndex_) {
      memoIndex_ = sampleIndex;
      memoReversedIndex_ = reverseBits32(sampleIndex);
    }
    return memoReversedIndex_;
  }

  uint64_t key_ = 0;               // hash of (seed, pixel) or (seed, Morton code above the tile bits)
  uint32_t reversedIndex_ = 0;     // the sequence index before shuffling, bit-reversed
  uint32_t reversedIndexXor_ = 0;  // zsobol: sample index bits above m, bit-reversed
  uint32_t request_ = 0;           // requests since the start
  uint64_t hash_ = 0;              // requestHash(key_, request_)
  uint32_t index_ = 0;             // request_'s shuffled index (bit-reversed)
  uint32_t sampleIndex_ = 0;
  uint32_t reversedTileCode_ = 0;  // zsobol: the pixel's Morton code within its tile, bit-reversed
  uint32_t log2Samples_ = 0;       // zsobol: m
  bool zsobol_ = false;
  // Kept from the previous start: reverseBits32(memoIndex_); zsobol: the key of tile memoTile_.
  uint32_t memoIndex_ = 0, memoReversedIndex_ = 0;
  uint64_t memoTile_ = ~0ull, memoSeedHash_ = 0, memoTileKey_ = 0;
};

using SobolStream = BasicSobolStream<OwenScrambling>;

// One draw of a pixel sample's stream: next2D(j, n, k, m), or next2D(j, n) when m = 1 (next2D() when
// n = 1 too).
struct SobolDrawCall {
  uint32_t j, n, k, m;
};

// The request (the hash's index) each of `calls`, made in order after a start, draws its point with:
// what next2D's three forms do to the stream's request counter, for code that draws the points of
// many streams at once (the packet row loop).
inline std::vector<uint32_t> sobolRequests(const std::vector<SobolDrawCall>& calls) {
  std::vector<uint32_t> requests;
  uint32_t request = 0;
  for (const SobolDrawCall& c : calls) {
    const bool last = c.j + 1 >= c.n;
    if (c.m == 1) {
      requests.push_back(request);
      if (c.n == 1 || last) ++request;
    } else {
      requests.push_back(request + c.k);
      if (last && c.k + 1 >= c.m) request += c.m;
    }
  }
  return requests;
}

}  // namespace penumbra
