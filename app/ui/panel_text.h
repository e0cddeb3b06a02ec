// Help text in the panels: greyed and wrapped at the window's edge, so it is never cut off.
#pragma once

namespace penumbra::ui {

void hintText(const char* fmt, ...);

// Blocks of fixed height, so that nothing below a block whose content varies (with the strategy, a
// note that comes and goes) moves:
// the height `text` takes as a line of the panel, wrapped at the content region's edge, with the
// spacing after it;
float textBlockHeight(const char* text);
// the height of one row of widgets (a combo, an input field), with the spacing after it;
float frameRowHeight();
// moves the cursor down to `top` + `height` when less was drawn since `top` (a GetCursorPosY()).
void padBlockTo(float top, float height);

}  // namespace penumbra::ui
