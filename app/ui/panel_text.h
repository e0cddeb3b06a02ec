// Text and rows in the panels, laid out so that nothing is cut off at the column's edge.
#pragma once

struct ImVec4;

namespace penumbra::ui {

// Help text: greyed and wrapped at the window's edge.
void hintText(const char* fmt, ...);
// Text in `colour`, wrapped at the window's edge.
void colouredWrappedText(const ImVec4& colour, const char* fmt, ...);

// The width a button labelled `label` takes (its label's shown part and the frame's padding), and a
// radio button's (its circle, the inner spacing and the label).
float buttonWidth(const char* label);
float radioButtonWidth(const char* label);
// Keeps the next item, `width` wide, on the line of the last one when it fits before the content
// region's edge; otherwise it starts the next line.
void sameLineIfFits(float width);

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
