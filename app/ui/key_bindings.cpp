#include "app/ui/key_bindings.h"

#include <bit>
#include <cstring>

namespace penumbra::ui {

namespace {

constexpr KeyBinding kBindings[] = {
    {Trigger::Key, " ", kNoModifier, ViewerAction::TogglePause, "Space", "pause / resume"},
    {Trigger::Key, "rR", kNoModifier, ViewerAction::Restart, "R", "restart accumulation"},
    {Trigger::Key, "sS", kNoModifier, ViewerAction::SavePng, "S",
     "save the display as PNG (path in the Display panel)"},
    {Trigger::Key, "fF", kNoModifier, ViewerAction::FitImage, "F", "fit the image to the window / reset pan"},
    {Trigger::Key, "+=", kNoModifier, ViewerAction::ExposureUp, "+", "exposure up by 1/2 stop"},
    {Trigger::Key, "-_", kNoModifier, ViewerAction::ExposureDown, "-", "exposure down by 1/2 stop"},
    {Trigger::Key, "hH?", kNoModifier, ViewerAction::ToggleHelp, "H", "show / hide this help"},
    {Trigger::LeftDrag, "", kNoModifier, ViewerAction::Orbit, "left drag",
     "orbit the camera about its target"},
    {Trigger::LeftDragOnDivider, "", kNoModifier, ViewerAction::MoveDivider, "left drag on the divider",
     "compare mode: move the split line"},
    {Trigger::RightOrMiddleDrag, "", kNoModifier, ViewerAction::Pan, "right / middle drag", "pan the camera"},
    {Trigger::Wheel, "", kNoModifier, ViewerAction::Dolly, "wheel", "dolly"},
    {Trigger::Wheel, "", kCtrl, ViewerAction::ZoomDisplay, "Ctrl + wheel", "zoom the display"},
};

bool triggers(const KeyBinding& b, Trigger trigger, char32_t ch) {
  if (b.trigger != trigger) return false;
  if (trigger != Trigger::Key) return true;
  return ch != 0 && ch < 128 && std::strchr(b.chars, int(ch)) != nullptr;
}

}  // namespace

std::span<const KeyBinding> keyBindings() {
  return kBindings;
}

const KeyBinding* findBinding(Trigger trigger, unsigned held, char32_t ch) {
  const KeyBinding* best = nullptr;
  for (const KeyBinding& b : kBindings)
    if (triggers(b, trigger, ch) && (b.modifiers & held) == b.modifiers &&
        (!best || std::popcount(b.modifiers) > std::popcount(best->modifiers)))
      best = &b;
  return best;
}

}  // namespace penumbra::ui
