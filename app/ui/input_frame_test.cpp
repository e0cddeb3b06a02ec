#include "app/ui/input_frame.h"

#include <gtest/gtest.h>
#include <imgui.h>

using namespace penumbra::ui;

TEST(InputFrame, LogLinesRoundTrip) {
  InputFrame in;
  in.x = 512.5f, in.y = 300;
  in.buttons = 5;
  in.wheel = -3;
  in.key = ImGuiKey_Enter;
  in.ctrl = true;
  in.shift = true;
  for (std::string text : {std::string(""), std::string("3e9"), std::string("a \"quoted\" \\ path"),
                           std::string("\xc3\xa9t\xc3\xa9\n\t"), std::string("\\x41")}) {
    in.text = text;
    InputFrame out;
    ASSERT_TRUE(parseInput(formatInput(in), out)) << formatInput(in);
    EXPECT_EQ(out.x, in.x);
    EXPECT_EQ(out.y, in.y);
    EXPECT_EQ(out.buttons, in.buttons);
    EXPECT_EQ(out.wheel, in.wheel);
    EXPECT_EQ(out.key, in.key);
    EXPECT_EQ(out.ctrl, in.ctrl);
    EXPECT_EQ(out.shift, in.shift);
    EXPECT_EQ(out.text, text) << formatInput(in);
  }
  InputFrame none, out;
  ASSERT_TRUE(parseInput(formatInput(none), out)) << formatInput(none);
  EXPECT_EQ(out.key, -1);
  EXPECT_FALSE(out.ctrl);
  EXPECT_FALSE(out.shift);
}

TEST(InputFrame, MalformedLogLinesAreRejected) {
  InputFrame out;
  EXPECT_FALSE(parseInput("", out));
  EXPECT_FALSE(parseInput("1 2 0 0 - -", out));           // no text
  EXPECT_FALSE(parseInput("1 2 0 0 Nope - \"\"", out));   // unknown key
  EXPECT_FALSE(parseInput("1 2 0 0 - - \"abc", out));     // unterminated
  EXPECT_FALSE(parseInput("1 2 0 0 - - \"\\x4\"", out));  // short escape
  EXPECT_FALSE(parseInput("x 2 0 0 - - \"\"", out));      // not a number
}

TEST(InputFrame, ApplySetsImGuisInputForOneFrame) {
  ImGuiContext* ctx = ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  installIdentityKeyMap(io);
  InputFrame in;
  in.x = 10, in.y = 20;
  in.buttons = 2;
  in.wheel = 1.5f;
  in.key = ImGuiKey_Tab;
  in.ctrl = true;
  in.text = "nan";
  applyInput(in, io);
  EXPECT_EQ(io.MousePos.x, 10.f);
  EXPECT_EQ(io.MousePos.y, 20.f);
  EXPECT_FALSE(io.MouseDown[0]);
  EXPECT_TRUE(io.MouseDown[1]);
  EXPECT_EQ(io.MouseWheel, 1.5f);
  EXPECT_TRUE(io.KeysDown[io.KeyMap[ImGuiKey_Tab]]);
  EXPECT_FALSE(io.KeysDown[io.KeyMap[ImGuiKey_Enter]]);
  EXPECT_TRUE(io.KeyCtrl);
  EXPECT_FALSE(io.KeyShift);
  ASSERT_EQ(io.InputQueueCharacters.Size, 3);
  EXPECT_EQ(io.InputQueueCharacters[0], 'n');

  InputFrame away;  // outside the window, nothing held
  applyInput(away, io);
  EXPECT_LT(io.MousePos.x, -1e30f);
  EXPECT_FALSE(io.MouseDown[1]);
  EXPECT_FALSE(io.KeysDown[io.KeyMap[ImGuiKey_Tab]]);
  ImGui::DestroyContext(ctx);
}
