#include "app/ui/key_bindings.h"

#include <gtest/gtest.h>

#include <set>

namespace penumbra::ui {
namespace {

ViewerAction actionOf(Trigger t, unsigned held, char32_t ch = 0) {
  const KeyBinding* b = findBinding(t, held, ch);
  EXPECT_NE(b, nullptr);
  return b ? b->action : ViewerAction::TogglePause;
}

TEST(KeyBindings, EveryActionIsBoundOnceAndListed) {
  std::set<ViewerAction> seen;
  for (const KeyBinding& b : keyBindings()) {
    EXPECT_TRUE(seen.insert(b.action).second) << b.label;
    EXPECT_NE(std::string(b.label), "");
    EXPECT_NE(std::string(b.help), "");
    if (b.trigger == Trigger::Key) {
      EXPECT_NE(std::string(b.chars), "") << b.label;
    }
  }
  EXPECT_EQ(seen.size(), size_t(ViewerAction::ZoomDisplay) + 1);
}

TEST(KeyBindings, KeysOfEitherCaseFindTheirAction) {
  EXPECT_EQ(actionOf(Trigger::Key, kNoModifier, ' '), ViewerAction::TogglePause);
  EXPECT_EQ(actionOf(Trigger::Key, kNoModifier, 'r'), ViewerAction::Restart);
  EXPECT_EQ(actionOf(Trigger::Key, kNoModifier, 'R'), ViewerAction::Restart);
  EXPECT_EQ(actionOf(Trigger::Key, kNoModifier, '='), ViewerAction::ExposureUp);
  EXPECT_EQ(actionOf(Trigger::Key, kNoModifier, '_'), ViewerAction::ExposureDown);
  EXPECT_EQ(actionOf(Trigger::Key, kNoModifier, '?'), ViewerAction::ToggleHelp);
  EXPECT_EQ(findBinding(Trigger::Key, kNoModifier, 'x'), nullptr);
  EXPECT_EQ(findBinding(Trigger::Key, kNoModifier, 0), nullptr);
  EXPECT_EQ(findBinding(Trigger::Key, kNoModifier, U'é'), nullptr);
}

TEST(KeyBindings, ModifiersPickTheMostSpecificBinding) {
  EXPECT_EQ(actionOf(Trigger::Wheel, kNoModifier), ViewerAction::Dolly);
  EXPECT_EQ(actionOf(Trigger::Wheel, kCtrl), ViewerAction::ZoomDisplay);
  // A modifier no binding asks for changes nothing.
  EXPECT_EQ(actionOf(Trigger::LeftDrag, kCtrl), ViewerAction::Orbit);
  EXPECT_EQ(actionOf(Trigger::Key, kCtrl, 'r'), ViewerAction::Restart);
}

}  // namespace
}  // namespace penumbra::ui
