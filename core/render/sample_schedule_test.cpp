#include "core/render/sample_schedule.h"

#include <gtest/gtest.h>

#include <vector>

namespace penumbra {
namespace {

TEST(SampleSchedule, DefaultIsPassEqualsIndex) {
  SampleSchedule s;
  for (uint64_t p = 0; p < 100; ++p) EXPECT_EQ(s.sampleIndex(p), p);
  EXPECT_EQ(s.passesBelow(37), 37u);
}

// Every index below n is rendered by exactly one part, within passesBelow(n) passes of that part,
// and every part's blocks are aligned runs of blockSize consecutive indices.
TEST(SampleSchedule, PartsCoverEachIndexOnceWithAlignedBlocks) {
  for (uint32_t block : {1u, 4u, 16u})
    for (uint32_t parts : {1u, 2u, 3u, 5u})
      for (uint64_t n : {0ull, 1ull, 7ull, 16ull, 33ull, 100ull, 257ull}) {
        std::vector<int> hits(n, 0);
        uint64_t total = 0;
        for (uint32_t r = 0; r < parts; ++r) {
          SampleSchedule s = SampleSchedule::blocks(block, r, parts);
          const uint64_t passes = s.passesBelow(n);
          total += passes;
          for (uint64_t p = 0; p < passes; ++p) {
            const uint64_t i = s.sampleIndex(p);
            ASSERT_LT(i, n) << "block " << block << " parts " << parts << " part " << r << " pass " << p;
            ++hits[i];
            EXPECT_EQ(i % block, p % block);            // aligned: a block starts at a multiple of its size
            EXPECT_EQ((i / block) % parts, r % parts);  // block b belongs to part b mod K
          }
          EXPECT_GE(s.sampleIndex(passes), n);  // the next pass is past n
        }
        EXPECT_EQ(total, n);
        for (uint64_t i = 0; i < n; ++i) EXPECT_EQ(hits[i], 1) << "index " << i;
      }
}

}  // namespace
}  // namespace penumbra
