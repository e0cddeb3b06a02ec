#include "app/ui/monkey.h"

#include <algorithm>
#include <iterator>

#include <imgui.h>

namespace penumbra::ui {

namespace {

// What a user types into number boxes, sliders (Ctrl+click), file names and search fields.
const char* const kValues[] = {"0",
                               "1",
                               "-1",
                               "-7",
                               "2",
                               "16",
                               "255",
                               "1024",
                               "65536",
                               "3e9",
                               "4294967296",
                               "2147483647",
                               "-2147483648",
                               "99999999999",
                               "1e38",
                               "-1e38",
                               "1e-45",
                               "-0",
                               "0.5",
                               "nan",
                               "NaN",
                               "-nan",
                               "inf",
                               "-inf",
                               "1e999",
                               "abc",
                               "",
                               " ",
                               "12abc",
                               "0x10",
                               "1,5",
                               "+",
                               "penumbra.png",
                               "out.exr",
                               "out.pfm",
                               "out.jpg",
                               "scene-live.xml",
                               "nope.xml",
                               ".",
                               "..",
                               "x.png",
                               "\xc3\xa9t\xc3\xa9.png"};

// Characters the viewer binds (app/ui/key_bindings.cpp) and a few it does not.
const char kViewerKeys[] = " rRsSfFhH+-=eEqwzx019";

}  // namespace

InputFrame& Monkey::push() {
  InputFrame f;
  f.x = pointer_.x;
  f.y = pointer_.y;
  queue_.push_back(f);
  return queue_.back();
}

void Monkey::pickPoint(const MonkeyView& view, bool onWidget, float& x, float& y) {
  std::vector<const RecordedItem*> visible;
  if (onWidget)
    for (const RecordedItem& it : view.items)
      if (it.id != 0 && it.x1 > 0 && it.y1 > 0 && it.x0 < view.width && it.y0 < view.height &&
          it.x1 > it.x0 && it.y1 > it.y0)
        visible.push_back(&it);
  if (visible.empty()) {
    x = uniform01() * view.width;
    y = uniform01() * view.height;
    return;
  }
  const RecordedItem& it = *visible[uniform(int(visible.size()))];
  x = std::clamp(it.x0 + uniform01() * (it.x1 - it.x0), 0.f, view.width - 1);
  y = std::clamp(it.y0 + uniform01() * (it.y1 - it.y0), 0.f, view.height - 1);
}

void Monkey::click(float x, float y, unsigned button, bool ctrl, int holdFrames) {
  pointer_.x = x, pointer_.y = y;
  push();  // move there first: ImGui hovers before it clicks
  for (int i = 0; i < holdFrames; ++i) {
    InputFrame& f = push();
    f.buttons = 1u << button;
    f.ctrl = ctrl;
  }
  push();  // release
}

void Monkey::pressKey(int key, bool ctrl, bool shift) {
  InputFrame& f = push();
  f.key = key;
  f.ctrl = ctrl;
  f.shift = shift;
  push();  // released: the next press of the same key is a new press
}

std::string Monkey::value(const MonkeyView& view) {
  if (!view.paths.empty() && chance(0.1f)) return view.paths[uniform(int(view.paths.size()))];
  if (chance(0.15f)) {  // random printable text, no path separators (files stay in the working directory)
    std::string s;
    for (int n = 1 + uniform(12); n > 0; --n) {
      char c = char(' ' + uniform(95));
      s += c == '/' || c == '\\' ? '_' : c;
    }
    return s;
  }
  return kValues[uniform(int(std::size(kValues)))];
}

void Monkey::typeValue(const MonkeyView& view) {
  float x, y;
  pickPoint(view, true, x, y);
  // Ctrl+click turns a slider or drag into a number box; a double click selects a word.
  const bool ctrl = chance(0.3f);
  click(x, y, 0, ctrl, 1);
  if (chance(0.2f)) click(x, y, 0, false, 1);
  if (chance(0.8f)) pressKey(ImGuiKey_A, true, false);  // select all
  if (chance(0.1f)) pressKey(ImGuiKey_Backspace, false, false);
  push().text = value(view);
  push();
  const float r = uniform01();
  if (r < 0.7f)
    pressKey(chance(0.8f) ? ImGuiKey_Enter : ImGuiKey_KeyPadEnter, false, false);
  else if (r < 0.8f)
    pressKey(ImGuiKey_Tab, false, chance(0.3f));
  else if (r < 0.9f)
    pressKey(ImGuiKey_Escape, false, false);
  // else: left active; the next gesture clicks elsewhere
}

void Monkey::drag(const MonkeyView& view) {
  float x0, y0, x1, y1;
  pickPoint(view, chance(0.5f), x0, y0);
  if (chance(0.5f)) {  // a short drag: sliders, the divider, the column's edge
    x1 = x0 + (uniform01() - 0.5f) * 200.f;
    y1 = y0 + (uniform01() - 0.5f) * 60.f;
  } else {
    pickPoint(view, false, x1, y1);
  }
  if (chance(0.05f)) x1 = -50.f;  // leave the window while dragging
  const float r = uniform01();
  const unsigned button = r < 0.6f ? 0 : r < 0.85f ? 1 : 2;
  const bool ctrl = chance(0.15f);
  pointer_.x = x0, pointer_.y = y0;
  push();
  InputFrame& down = push();
  down.buttons = 1u << button;
  down.ctrl = ctrl;
  const int steps = 2 + uniform(14);
  for (int i = 1; i <= steps; ++i) {
    const float t = float(i) / steps;
    InputFrame& f = push();
    f.x = x0 + (x1 - x0) * t + (uniform01() - 0.5f) * 4.f;
    f.y = y0 + (y1 - y0) * t + (uniform01() - 0.5f) * 4.f;
    f.buttons = 1u << button;
    f.ctrl = ctrl;
    if (chance(0.05f)) f.buttons |= 1u << ((button + 1) % 3);  // a second button joins in
  }
  pointer_.x = queue_.back().x, pointer_.y = queue_.back().y;
  push();  // release
}

void Monkey::plan(const MonkeyView& view) {
  const float r = uniform01();
  float x, y;
  if (r < 0.30f) {  // click, mostly on a widget; sometimes right/middle, double, held or with Ctrl
    pickPoint(view, chance(0.8f), x, y);
    const float b = uniform01();
    const unsigned button = b < 0.8f ? 0 : b < 0.9f ? 1 : 2;
    const int hold = chance(0.15f) ? 2 + uniform(30) : 1;  // held: an InputInt's +/- repeats
    click(x, y, button, chance(0.05f), hold);
    if (chance(0.15f)) click(x, y, button, false, 1);
  } else if (r < 0.50f) {
    typeValue(view);
  } else if (r < 0.65f) {
    drag(view);
  } else if (r < 0.75f) {  // wheel over the image (dolly, zoom with Ctrl) or a panel (scroll)
    pickPoint(view, chance(0.3f), x, y);
    pointer_.x = x, pointer_.y = y;
    push();
    const float steps[] = {1, -1, 3, -3, 0.5f, -0.5f, 10, -10, 120, -120};
    InputFrame& f = push();
    f.wheel = steps[uniform(int(std::size(steps)))];
    f.ctrl = chance(0.3f);
  } else if (r < 0.87f) {  // the viewer's keys, typed while no text field is active
    push().text = std::string(1, kViewerKeys[uniform(int(std::size(kViewerKeys)) - 1)]);
    push();
  } else if (r < 0.94f) {  // ImGui's keys: focus, editing, closing popups
    pressKey(uniform(ImGuiKey_COUNT), chance(0.3f), chance(0.2f));
  } else if (r < 0.97f) {  // hover: the pixel inspector, tooltips
    pickPoint(view, chance(0.5f), x, y);
    pointer_.x = x, pointer_.y = y;
    for (int n = 1 + uniform(4); n > 0; --n) push();
  } else {  // nothing for a few frames: passes arrive
    for (int n = 1 + uniform(6); n > 0; --n) push();
  }
}

InputFrame Monkey::next(const MonkeyView& view) {
  if (queue_.empty()) plan(view);
  InputFrame f = queue_.front();
  queue_.pop_front();
  return f;
}

}  // namespace penumbra::ui
