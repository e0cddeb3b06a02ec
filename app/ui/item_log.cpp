#include "app/ui/item_log.h"

#include <cstdio>
#include <map>
#include <utility>

namespace penumbra::ui {

namespace {
ItemLog* gActive = nullptr;

std::string rectText(const RecordedItem& r) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.0f, %.0f)-(%.0f, %.0f)", r.x0, r.y0, r.x1, r.y1);
  return buf;
}
}  // namespace

ItemLog* activeItemLog() {
  return gActive;
}

void setActiveItemLog(ItemLog* log) {
  gActive = log;
}

std::string DuplicateId::describe() const {
  char id[16];
  std::snprintf(id, sizeof id, "0x%08x", this->id);
  return "window \"" + window + "\": two widgets share the ID " + id +
         (label.empty() ? std::string() : " (label \"" + label + "\")") + ", at " + rectText(first) +
         " and " + rectText(second);
}

void ItemLog::beginFrame() {
  items_.clear();
}

void ItemLog::add(std::uint32_t id, std::uint32_t window, const char* windowName, float x0, float y0,
                  float x1, float y1) {
  items_.push_back(RecordedItem{id, window, x0, y0, x1, y1});
  ++totalAdded_;
  auto it = windowNames_.find(window);
  if (it == windowNames_.end()) windowNames_.emplace(window, windowName ? windowName : "?");
}

void ItemLog::noteLabel(std::uint32_t id, const char* begin, const char* end) {
  if (labels_.count(id)) return;
  labels_.emplace(id, end ? std::string(begin, end) : std::string(begin));
}

const std::string& ItemLog::windowName(std::uint32_t window) const {
  static const std::string unknown = "?";
  auto it = windowNames_.find(window);
  return it == windowNames_.end() ? unknown : it->second;
}

std::string ItemLog::labelOf(std::uint32_t id) const {
  auto it = labels_.find(id);
  return it == labels_.end() ? std::string() : it->second;
}

std::vector<DuplicateId> ItemLog::duplicates() const {
  std::vector<DuplicateId> out;
  std::map<std::pair<std::uint32_t, std::uint32_t>, size_t> seen;  // (window, id) -> first item
  for (size_t i = 0; i < items_.size(); ++i) {
    const RecordedItem& item = items_[i];
    if (item.id == 0) continue;
    auto [it, fresh] = seen.emplace(std::make_pair(item.window, item.id), i);
    if (fresh) continue;
    DuplicateId d;
    d.id = item.id;
    d.window = windowName(item.window);
    d.label = labelOf(item.id);
    d.first = items_[it->second];
    d.second = item;
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace penumbra::ui
