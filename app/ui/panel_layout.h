// The panel column's width, without GL: how much of the window the panels take when the user has
// not dragged the column's edge, and the label column inside it. A small window keeps most of its
// width for the image (docs/viewer.md, "Layout").
#pragma once

namespace penumbra::ui {

// 5/16 of the window's width (400 px at 1280 wide), between 260 and 560 px, and never more than
// 40 % of the window (640 wide: 256 px of panels, 384 of image).
int defaultSidebarWidth(int windowWidth);
// The range a drag of the column's edge may choose.
int minSidebarWidth(int windowWidth);
int maxSidebarWidth(int windowWidth);
// Width of the label column right of the widgets: 150 px, down to 112 px (the longest label, "light
// selection", and its spacing) in a narrow column so the widgets keep room for their values.
float labelColumnWidth(int sidebarWidth);

}  // namespace penumbra::ui
