#include "core/math/utf8.h"

#include <gtest/gtest.h>

#include <string>

namespace penumbra {
namespace {

constexpr size_t npos = std::string_view::npos;

TEST(Utf8, WellFormedTextPasses) {
  EXPECT_EQ(invalidUtf8Offset(""), npos);
  EXPECT_EQ(invalidUtf8Offset("plain ascii <scene/>"), npos);
  EXPECT_EQ(invalidUtf8Offset("\xEF\xBB\xBF"
                              "caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80"),
            npos);                                         // BOM, é, €, 😀
  EXPECT_EQ(invalidUtf8Offset("\xF4\x8F\xBF\xBF"), npos);  // U+10FFFF
}

TEST(Utf8, IllFormedSequencesAreFoundAtTheirFirstByte) {
  EXPECT_EQ(invalidUtf8Offset("ab\xFF"), 2u);
  EXPECT_EQ(invalidUtf8Offset("ab\xC3"), 2u);            // truncated
  EXPECT_EQ(invalidUtf8Offset("\xC0\xAF"), 0u);          // overlong '/'
  EXPECT_EQ(invalidUtf8Offset("x\xE0\x80\xAF"), 1u);     // overlong, 3 bytes
  EXPECT_EQ(invalidUtf8Offset("\xED\xA0\x80"), 0u);      // a surrogate
  EXPECT_EQ(invalidUtf8Offset("\xF4\x90\x80\x80"), 0u);  // above U+10FFFF
  EXPECT_EQ(invalidUtf8Offset("caf\xC3\xA9\x80"), 5u);   // a stray continuation byte
  EXPECT_EQ(invalidUtf8Offset("latin-1 caf\xE9!"), 11u);
}

TEST(Utf8, EscapingKeepsValidTextAndSpellsOutTheRest) {
  EXPECT_EQ(escapeInvalidUtf8("caf\xC3\xA9"), "caf\xC3\xA9");
  EXPECT_EQ(escapeInvalidUtf8("caf\xE9!"), "caf\\xE9!");
  EXPECT_EQ(escapeInvalidUtf8(std::string("a\0b", 3)), "a\\x00b");
  EXPECT_EQ(invalidUtf8Offset(escapeInvalidUtf8("\xFF\xFE\xC3")), npos);
}

}  // namespace
}  // namespace penumbra
