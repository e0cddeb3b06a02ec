// ImGui widgets for the numeric fields of app/ui/number_field.h: a text field with − / + step
// buttons, and a slider, both clamping to the field's range; a grey line under the widget says what
// was done to the last value entered ("clamped to 16777216 (the largest sampleCount)") until the
// next one. IDs: the label's (its text before "##" is shown), with "##text", "##less", "##more" under it.
#pragma once

#include <optional>

#include "app/ui/number_field.h"

namespace penumbra::ui {

// A typed value is taken on Enter or when the field loses focus; the step buttons add or take
// `step` (`fastStep` with Ctrl held). Returns the new value within the range, once, when one was
// entered.
std::optional<double> numberInput(const char* label, const NumberField& field, double current, double step,
                                  double fastStep);
// A slider over [dragMin, dragMax] (a sub-range of the field's, or all of it); a value typed with
// Ctrl+click may go beyond the drag range up to the field's. True when `value` changed.
bool numberSlider(const char* label, const NumberField& field, float& value, float dragMin, float dragMax,
                  const char* format, int sliderFlags = 0);
// Forgets the notes (a new scene: they were about the old one's values).
void forgetNumberNotes();

}  // namespace penumbra::ui
