// The ImGui items (widgets) each frame registers, with their IDs, rectangles and windows: the monkey
// test clicks on the last frame's items, and the widget-ID audit fails when two items of one window
// share an ID (ImGui then treats them as one widget: a click on one activates the other, which
// trips ImGui's asserts). Filled by app/ui/imgui_item_hook.cpp, which wraps ImGui::ItemAdd and
// ImGuiWindow::GetID at link time; only penumbra-offscreen links it.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace penumbra::ui {

struct RecordedItem {
  std::uint32_t id = 0;
  std::uint32_t window = 0;  // the ImGui window's ID
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Two items of one window with one ID, in one frame.
struct DuplicateId {
  std::uint32_t id = 0;
  std::string window;  // its name
  std::string label;   // the label the ID was hashed from ("" when ImGui hashed it internally)
  RecordedItem first, second;
  std::string describe() const;
};

class ItemLog {
 public:
  // Forgets the items of the previous frame (labels are kept: IDs are stable).
  void beginFrame();
  void add(std::uint32_t id, std::uint32_t window, const char* windowName, float x0, float y0, float x1,
           float y1);
  void noteLabel(std::uint32_t id, const char* begin, const char* end);
  const std::vector<RecordedItem>& items() const { return items_; }
  const std::string& windowName(std::uint32_t window) const;
  // The label an ID was hashed from ("" when unknown).
  std::string labelOf(std::uint32_t id) const;
  // Items added in this process so far: 0 when the hook is not linked.
  std::uint64_t totalAdded() const { return totalAdded_; }
  // The IDs of this frame that two items of one window share (ID 0, ImGui's "no ID", excepted).
  std::vector<DuplicateId> duplicates() const;

 private:
  std::vector<RecordedItem> items_;
  std::unordered_map<std::uint32_t, std::string> windowNames_;
  std::unordered_map<std::uint32_t, std::string> labels_;
  std::uint64_t totalAdded_ = 0;
};

// The log the hook writes into (nullptr: none; the hook then only forwards to ImGui).
ItemLog* activeItemLog();
void setActiveItemLog(ItemLog* log);

}  // namespace penumbra::ui
