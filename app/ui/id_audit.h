// The widget-ID audit (`penumbra view --audit-ids`, docs/viewer.md "Robustness"): draws the panels in
// every state a scene offers — each strategy with each light selection and each sampler, the time
// budget, compare mode with each right-side strategy, the MIS light-share view, help and warp
// inspector windows — then clicks every widget once (opening combos, popups, tree nodes and text
// fields) and records each frame's items (app/ui/item_log.h). It fails when two widgets of one
// window share an ID, naming the state, the window, the label and both rectangles.
#pragma once

#include <memory>

#include "app/ui/frame_driver.h"

namespace penumbra::ui {

std::shared_ptr<FrameDriver> makeIdAuditDriver();

}  // namespace penumbra::ui
