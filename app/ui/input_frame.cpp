#include "app/ui/input_frame.h"

#include <cctype>
#include <cfloat>
#include <cstdio>
#include <cstring>
#include <sstream>

#include <imgui.h>

namespace penumbra::ui {

namespace {

const char* const kKeyNames[ImGuiKey_COUNT] = {
    "Tab", "LeftArrow", "RightArrow", "UpArrow",   "DownArrow", "PageUp", "PageDown", "Home",
    "End", "Insert",    "Delete",     "Backspace", "Space",     "Enter",  "Escape",   "KeyPadEnter",
    "A",   "C",         "V",          "X",         "Y",         "Z"};

std::string escape(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += char(c);
    } else if (c < 0x20 || c >= 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += char(c);
    }
  }
  return out + "\"";
}

bool unescape(const std::string& quoted, std::string& out) {
  if (quoted.size() < 2 || quoted.front() != '"' || quoted.back() != '"') return false;
  const std::string s = quoted.substr(1, quoted.size() - 2);
  out.clear();
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '\\') {
      out += s[i];
    } else if (i + 1 < s.size() && s[i + 1] != 'x') {
      out += s[++i];
    } else if (i + 3 < s.size()) {  // \xHH
      if (!std::isxdigit((unsigned char)s[i + 2]) || !std::isxdigit((unsigned char)s[i + 3])) return false;
      out += char(std::stoi(s.substr(i + 2, 2), nullptr, 16));
      i += 3;
    } else {
      return false;
    }
  }
  return true;
}

}  // namespace

const char* keyName(int key) {
  return key >= 0 && key < ImGuiKey_COUNT ? kKeyNames[key] : "-";
}

void installIdentityKeyMap(ImGuiIO& io) {
  for (int k = 0; k < ImGuiKey_COUNT; ++k) io.KeyMap[k] = k;
}

void applyInput(const InputFrame& in, ImGuiIO& io) {
  io.MousePos = in.x < 0 || in.y < 0 ? ImVec2(-FLT_MAX, -FLT_MAX) : ImVec2(in.x, in.y);
  for (int b = 0; b < 5; ++b) io.MouseDown[b] = (in.buttons >> b) & 1u;
  io.MouseWheel = in.wheel;
  io.MouseWheelH = 0;
  for (int k = 0; k < ImGuiKey_COUNT; ++k) io.KeysDown[io.KeyMap[k]] = k == in.key;
  io.KeyCtrl = in.ctrl;
  io.KeyShift = in.shift;
  io.KeyAlt = io.KeySuper = false;
  if (!in.text.empty()) io.AddInputCharactersUTF8(in.text.c_str());
}

std::string formatInput(const InputFrame& in) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%.1f %.1f %u %g %s %s%s ", in.x, in.y, in.buttons, in.wheel,
                keyName(in.key), in.ctrl ? "C" : "", in.shift ? "S" : (in.ctrl ? "" : "-"));
  return buf + escape(in.text);
}

bool parseInput(const std::string& line, InputFrame& out) {
  std::istringstream is(line);
  std::string key, mods;
  InputFrame in;
  if (!(is >> in.x >> in.y >> in.buttons >> in.wheel >> key >> mods)) return false;
  in.key = -1;
  if (key != "-") {
    for (int k = 0; k < ImGuiKey_COUNT; ++k)
      if (key == kKeyNames[k]) in.key = k;
    if (in.key < 0) return false;
  }
  in.ctrl = mods.find('C') != std::string::npos;
  in.shift = mods.find('S') != std::string::npos;
  std::string rest;
  std::getline(is >> std::ws, rest);
  if (!unescape(rest, in.text)) return false;
  out = in;
  return true;
}

}  // namespace penumbra::ui
