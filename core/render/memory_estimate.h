// What a render of a given image size allocates, checked before allocating: a 16384^2 film is
// ~30 GB, and running out half-way through (std::bad_alloc, or the OOM killer) says nothing useful.
#pragma once

#include <cstdint>
#include <string>

#include "core/math/error.h"

namespace penumbra {

// Per pixel: the film's six double sums (48 B) and up to five float RGB images at once (the
// published snapshot, the one being resolved, the reader's copy, the written mean and a standard
// error), 12 B each.
inline constexpr uint64_t kRenderBytesPerPixel = 48 + 5 * 12;

// Work refused because it would not fit in memory (an Error: the CLI exits with 2; Python raises
// MemoryError).
class OutOfMemoryError : public Error {
 public:
  using Error::Error;
};

uint64_t estimateRenderBytes(int width, int height);

// Memory this process can still get: MemAvailable (/proc/meminfo), lowered by what RLIMIT_AS and
// RLIMIT_DATA still allow when they are set (the limit minus the address space or data segment
// already in use). 0 if unknown.
uint64_t availableMemoryBytes();

// Throws OutOfMemoryError("<what>: a WxH render needs about N GB, only M GB available") when the
// estimate does not fit in availableMemoryBytes(); `available` overrides the measurement (tests).
void checkRenderFitsInMemory(int width, int height, const std::string& what, uint64_t available = 0);
// The same for `bytes` of anything else: "<what> needs about N GB, only M GB available".
void checkFitsInMemory(uint64_t bytes, const std::string& what, uint64_t available = 0);

// "22.3 GB", "512 MB": for messages.
std::string formatBytes(uint64_t bytes);

}  // namespace penumbra
