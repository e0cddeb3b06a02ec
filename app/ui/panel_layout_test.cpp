// The panel column leaves most of a small window to the image, and the compare divider keeps a dark
// outline around its light core.
#include "app/ui/panel_layout.h"

#include <gtest/gtest.h>

#include "app/ui/divider_columns.h"

using namespace penumbra::ui;

TEST(PanelLayout, TheColumnShrinksWithTheWindow) {
  EXPECT_EQ(defaultSidebarWidth(1280), 400);
  EXPECT_EQ(defaultSidebarWidth(1920), 560);
  EXPECT_EQ(defaultSidebarWidth(640), 256);
  for (int w : {640, 800, 1024, 1280, 1920, 3840}) {
    EXPECT_LE(defaultSidebarWidth(w), w * 2 / 5) << w;  // the image keeps at least 60 %
    EXPECT_GE(defaultSidebarWidth(w), minSidebarWidth(w)) << w;
    EXPECT_LE(defaultSidebarWidth(w), maxSidebarWidth(w)) << w;
  }
  EXPECT_EQ(defaultSidebarWidth(480), minSidebarWidth(480));  // below 640 wide: the narrowest column
  EXPECT_EQ(labelColumnWidth(400), 150.f);
  EXPECT_LT(labelColumnWidth(256), 120.f);  // the widgets keep room for their values
  EXPECT_GE(labelColumnWidth(200), 112.f);  // "light selection" fits
}

TEST(DividerColumns, ALightCoreBetweenTwoDarkOutlines) {
  const DividerColumns d = dividerColumns(500.f, 400, 900);
  EXPECT_EQ(d.coreEnd - d.coreStart, 2);
  EXPECT_EQ(d.coreStart - d.leftImageEnd, 1);
  EXPECT_EQ(d.rightImageStart - d.coreEnd, 1);
  EXPECT_LE(d.coreStart, 500);
  EXPECT_GE(d.coreEnd, 500);
  // Clipped at the visible image's edges.
  const DividerColumns edge = dividerColumns(400.2f, 400, 900);
  EXPECT_EQ(edge.leftImageEnd, 400);
  EXPECT_GE(edge.coreStart, 400);
  // Outline and core contrast whatever is under them.
  for (int c = 0; c < 3; ++c) EXPECT_GT(kDividerCoreRgb[c] - kDividerOutlineRgb[c], 0.8f);
}
