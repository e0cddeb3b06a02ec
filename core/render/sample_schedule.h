// Which sample indices an accumulation renders. Pass n (0, 1, 2, ...) of the engine renders sample
// index (firstBlock + (n / blockSize) * blockStride) * blockSize + n % blockSize in every pixel; the
// default (blocks of one, stride one) is pass n = index n. Processes that share one render (MPI
// ranks) take disjoint aligned blocks of a power-of-two size: rank r of K starts at block r with
// stride K, so the union of the first m blocks of every rank is the index prefix [0, m*K*blockSize)
// and a low-discrepancy sampler's nets of up to blockSize points stay whole within each rank.
#pragma once

#include <cstdint>

namespace penumbra {

struct SampleSchedule {
  uint32_t blockSize = 1;
  uint32_t firstBlock = 0;
  uint32_t blockStride = 1;

  // The partition of the indices among `parts` processes; this is part `part`.
  static SampleSchedule blocks(uint32_t blockSize, uint32_t part, uint32_t parts) {
    return SampleSchedule{blockSize, part, parts};
  }

  uint64_t sampleIndex(uint64_t pass) const {
    return (firstBlock + (pass / blockSize) * uint64_t(blockStride)) * blockSize + pass % blockSize;
  }
  // How many passes render an index below `n`: the passes [0, result) do, later ones do not (the
  // indices of a schedule increase with the pass). Over all parts of a partition these sum to n.
  uint64_t passesBelow(uint64_t n) const {
    const uint64_t fullBlocks = n / blockSize, rest = n % blockSize;
    uint64_t passes = 0;
    if (fullBlocks > firstBlock) passes += ((fullBlocks - firstBlock - 1) / blockStride + 1) * blockSize;
    if (rest > 0 && fullBlocks >= firstBlock && (fullBlocks - firstBlock) % blockStride == 0) passes += rest;
    return passes;
  }
};

}  // namespace penumbra
