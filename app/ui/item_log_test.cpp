#include "app/ui/item_log.h"

#include <gtest/gtest.h>

using namespace penumbra::ui;

TEST(ItemLog, TwoWidgetsOfOneWindowWithOneIdAreADuplicate) {
  ItemLog log;
  const char* label = "target spp";
  log.noteLabel(0xabcd, label, nullptr);
  log.add(0xabcd, 1, "Penumbra", 8, 400, 120, 420);  // the radio button
  log.add(0x1234, 1, "Penumbra", 8, 430, 300, 450);
  log.add(0xabcd, 1, "Penumbra", 8, 460, 300, 480);  // the number box
  std::vector<DuplicateId> d = log.duplicates();
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].id, 0xabcdu);
  EXPECT_EQ(d[0].window, "Penumbra");
  EXPECT_EQ(d[0].label, "target spp");
  EXPECT_EQ(d[0].first.y0, 400.f);
  EXPECT_EQ(d[0].second.y0, 460.f);
  const std::string text = d[0].describe();
  EXPECT_NE(text.find("\"Penumbra\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"target spp\""), std::string::npos) << text;
  EXPECT_NE(text.find("(8, 460)-(300, 480)"), std::string::npos) << text;
}

TEST(ItemLog, OtherWindowsIdZeroAndEarlierFramesAreNoDuplicates) {
  ItemLog log;
  log.add(7, 1, "Penumbra", 0, 0, 1, 1);
  log.add(7, 2, "Help", 0, 0, 1, 1);      // the same ID in another window
  log.add(0, 1, "Penumbra", 0, 0, 1, 1);  // text, separators: no ID
  log.add(0, 1, "Penumbra", 0, 0, 1, 1);
  EXPECT_TRUE(log.duplicates().empty());
  log.beginFrame();
  EXPECT_TRUE(log.items().empty());
  log.add(7, 1, "Penumbra", 0, 0, 1, 1);  // the next frame
  EXPECT_TRUE(log.duplicates().empty());
  EXPECT_EQ(log.totalAdded(), 5u);
  EXPECT_EQ(log.windowName(2), "Help");
}

TEST(ItemLog, TheHookWritesIntoTheActiveLogOnly) {
  EXPECT_EQ(activeItemLog(), nullptr);
  ItemLog log;
  setActiveItemLog(&log);
  EXPECT_EQ(activeItemLog(), &log);
  setActiveItemLog(nullptr);
}
