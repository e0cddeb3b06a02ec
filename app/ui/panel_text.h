// Help text in the panels: greyed and wrapped at the window's edge, so it is never cut off.
#pragma once

namespace penumbra::ui {

void hintText(const char* fmt, ...);

}  // namespace penumbra::ui
