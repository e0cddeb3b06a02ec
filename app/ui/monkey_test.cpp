#include "app/ui/monkey.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <set>

using namespace penumbra::ui;

namespace {

MonkeyView viewWithWidgets() {
  MonkeyView v;
  v.width = 1280, v.height = 800;
  for (int i = 0; i < 20; ++i)
    v.items.push_back(RecordedItem{std::uint32_t(100 + i), 1, 10, 30.f * i, 380, 30.f * i + 20});
  return v;
}

bool inside(const MonkeyView& v, float x, float y) {
  for (const RecordedItem& it : v.items)
    if (x >= it.x0 && x <= it.x1 && y >= it.y0 && y <= it.y1) return true;
  return false;
}

}  // namespace

TEST(Monkey, TheSameSeedGivesTheSameInput) {
  const MonkeyView v = viewWithWidgets();
  Monkey a(17), b(17), c(18);
  int differ = 0;
  for (int i = 0; i < 2000; ++i) {
    const InputFrame fa = a.next(v), fb = b.next(v), fc = c.next(v);
    ASSERT_EQ(formatInput(fa), formatInput(fb)) << "frame " << i;
    differ += formatInput(fa) != formatInput(fc);
  }
  EXPECT_GT(differ, 1000);
}

// Every kind of input the issue lists shows up in 20,000 frames, and presses favour widgets.
TEST(Monkey, ClicksDragsWheelKeysAndTypedValuesAllOccur) {
  const MonkeyView v = viewWithWidgets();
  Monkey m(3);
  std::set<unsigned> buttons;
  std::set<int> keys;
  std::set<std::string> texts;
  int presses = 0, pressesOnWidgets = 0, wheels = 0, dragFrames = 0, ctrlA = 0;
  InputFrame prev;
  for (int i = 0; i < 20000; ++i) {
    const InputFrame f = m.next(v);
    if (f.buttons && !prev.buttons) {
      ++presses;
      pressesOnWidgets += inside(v, f.x, f.y);
    }
    if (f.buttons && prev.buttons && (f.x != prev.x || f.y != prev.y)) ++dragFrames;
    for (unsigned b = 0; b < 3; ++b)
      if (f.buttons >> b & 1) buttons.insert(b);
    wheels += f.wheel != 0;
    if (f.key >= 0) keys.insert(f.key);
    ctrlA += f.key == ImGuiKey_A && f.ctrl;
    if (!f.text.empty()) texts.insert(f.text);
    EXPECT_EQ(f.text.find('/'), std::string::npos) << "typed a path out of the working directory";
    prev = f;
  }
  EXPECT_EQ(buttons.size(), 3u);
  EXPECT_GT(presses, 2000);
  EXPECT_GT(pressesOnWidgets, presses / 2);
  EXPECT_GT(dragFrames, 800);
  EXPECT_GT(wheels, 200);
  EXPECT_GT(ctrlA, 200);
  for (int k : {ImGuiKey_Enter, ImGuiKey_Tab, ImGuiKey_Escape, ImGuiKey_Backspace})
    EXPECT_TRUE(keys.count(k)) << k;
  for (const char* t : {"0", "-1", "3e9", "nan", "1e38", "abc", "r", " "}) EXPECT_TRUE(texts.count(t)) << t;
}

TEST(Monkey, TypesTheScenePathsItIsGiven) {
  MonkeyView v = viewWithWidgets();
  v.paths = {"/scenes/a.xml"};
  Monkey m(5);
  int typed = 0;
  for (int i = 0; i < 5000; ++i) typed += m.next(v).text == "/scenes/a.xml";
  EXPECT_GT(typed, 10);
}
