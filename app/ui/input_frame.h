// The mouse and keyboard state of one viewer frame, as a program sets it instead of a person (the
// monkey test): applied to ImGuiIO before the frame, and written one line per frame to a log that
// `penumbra view --monkey-replay` plays back exactly.
#pragma once

#include <string>

struct ImGuiIO;

namespace penumbra::ui {

struct InputFrame {
  float x = -1, y = -1;  // mouse position in pixels (negative: outside the window)
  unsigned buttons = 0;  // bit b: mouse button b held (0 left, 1 right, 2 middle)
  float wheel = 0;       // vertical wheel steps this frame
  int key = -1;          // an ImGuiKey_ held during this frame (-1: none)
  bool ctrl = false, shift = false;
  std::string text;  // characters typed this frame (UTF-8)
};

// Maps every ImGuiKey_ to its own index in io.KeysDown (the offscreen platform has no key codes).
void installIdentityKeyMap(ImGuiIO& io);
// Sets ImGui's input for the next frame: mouse, buttons, wheel, keys (only `key` down), modifiers,
// typed characters.
void applyInput(const InputFrame& in, ImGuiIO& io);

// "x y buttons wheel key mods text" with the text C-escaped in quotes, e.g. `512 300 1 0 -1 - ""`.
std::string formatInput(const InputFrame& in);
// The inverse of formatInput; false on a malformed line.
bool parseInput(const std::string& line, InputFrame& out);
// ImGuiKey_ name for logs ("Enter", "Tab", ...), "-" for none.
const char* keyName(int key);

}  // namespace penumbra::ui
