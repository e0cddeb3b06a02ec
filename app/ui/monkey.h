// The monkey: seeded random input for the viewer, as an impatient new user would give it. Clicks,
// double clicks, held buttons, drags (any button, over panels, the image, the divider and the column's
// edge), wheel turns, the viewer's keys and ImGui's editing keys, and typed values (0, negative,
// huge, 3e9, NaN, text, file names) followed by Enter, Tab or Escape. Half of the pointer gestures
// land on a widget of the last frame (app/ui/item_log.h), so combos, popups and text fields are
// reached as often as empty space.
#pragma once

#include <cstdint>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include "app/ui/input_frame.h"
#include "app/ui/item_log.h"

namespace penumbra::ui {

// What the monkey sees before a frame.
struct MonkeyView {
  float width = 0, height = 0;      // the window
  std::vector<RecordedItem> items;  // the last frame's widgets
  std::vector<std::string> paths;   // file names worth typing (nearby and recent scenes)
};

class Monkey {
 public:
  explicit Monkey(std::uint64_t seed) : rng_(seed) {}
  // The input of the next frame: the next step of the current gesture, or of a new one.
  InputFrame next(const MonkeyView& view);

 private:
  void plan(const MonkeyView& view);
  // A point: on a random widget of the last frame (when there is one and `onWidget`), else anywhere.
  void pickPoint(const MonkeyView& view, bool onWidget, float& x, float& y);
  void click(float x, float y, unsigned button, bool ctrl, int holdFrames);
  void typeValue(const MonkeyView& view);
  void drag(const MonkeyView& view);
  void pressKey(int key, bool ctrl, bool shift);
  std::string value(const MonkeyView& view);
  int uniform(int n) { return int(rng_() % std::uint64_t(n)); }
  float uniform01() { return float(rng_() >> 40) / float(1 << 24); }
  bool chance(float p) { return uniform01() < p; }
  // Queues a frame that keeps the pointer where the last one left it.
  InputFrame& push();

  std::mt19937_64 rng_;
  std::deque<InputFrame> queue_;
  InputFrame pointer_;  // the last queued frame's pointer (position persists between gestures)
};

}  // namespace penumbra::ui
