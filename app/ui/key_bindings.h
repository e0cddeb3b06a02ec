// The viewer's keyboard and mouse bindings, in one table: the input handler looks its actions up here
// and the help panel lists it.
#pragma once

#include <span>

namespace penumbra::ui {

enum class ViewerAction {
  TogglePause,
  Restart,
  SavePng,
  FitImage,
  ExposureUp,
  ExposureDown,
  ToggleHelp,
  Orbit,
  MoveDivider,
  Pan,
  Dolly,
  ZoomDisplay,
};

// What triggers a binding: a typed character, or a mouse gesture over the image area.
enum class Trigger { Key, LeftDrag, LeftDragOnDivider, RightOrMiddleDrag, Wheel };

// Modifier keys, as a bit set.
enum KeyModifier : unsigned { kNoModifier = 0, kCtrl = 1 };

struct KeyBinding {
  Trigger trigger;
  const char* chars;   // Trigger::Key: the characters that trigger it (both cases of a letter)
  unsigned modifiers;  // KeyModifier bits that must be held
  ViewerAction action;
  const char* label;  // the trigger as the help panel shows it
  const char* help;   // what it does
};

// Every binding, in the help panel's order.
std::span<const KeyBinding> keyBindings();

// The binding of `trigger` (and typed character `ch`, for Trigger::Key) while the `held` modifiers are
// down: of the bindings whose modifiers are all held, the one that needs the most. nullptr: none.
const KeyBinding* findBinding(Trigger trigger, unsigned held, char32_t ch = 0);

}  // namespace penumbra::ui
