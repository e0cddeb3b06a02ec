#include "app/ui/id_audit.h"

#include <cstdio>
#include <deque>
#include <functional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <imgui.h>

#include "app/ui/input_frame.h"
#include "app/ui/item_log.h"
#include "core/render/strategy_axes.h"
#include "core/sampling/sampler_table.h"

namespace penumbra::ui {

namespace {

// One frame of the audit: what it shows (for the report), the state it sets, the input it gives.
struct AuditFrame {
  std::string state;
  std::function<void(DrivenViewer&)> apply;  // may be empty
  InputFrame input;
};

class IdAuditDriver final : public FrameDriver {
 public:
  IdAuditDriver() { setActiveItemLog(&items_); }
  ~IdAuditDriver() override { setActiveItemLog(nullptr); }

  bool beforeFrame(int index, DrivenViewer& v) override {
    if (index == 0) {
      installIdentityKeyMap(ImGui::GetIO());
      planSettings(v.controller());
    }
    if (queue_.empty() && !walked_) {
      walked_ = true;
      planClickWalk(v);
    }
    if (queue_.empty()) return false;
    AuditFrame f = std::move(queue_.front());
    queue_.pop_front();
    if (f.apply) f.apply(v);
    state_ = f.state;
    items_.beginFrame();
    applyInput(f.input, ImGui::GetIO());
    return true;
  }

  bool afterFrame(int index, DrivenViewer&, double) override {
    ++frames_;
    if (index == 0 && items_.totalAdded() == 0) {
      std::fprintf(stderr,
                   "audit: no ImGui items were recorded: this binary lacks the item hook "
                   "(app/ui/imgui_item_hook.cpp; penumbra-offscreen links it)\n");
      hookMissing_ = true;
      return false;
    }
    for (const RecordedItem& it : items_.items()) ids_.insert(it.id);
    states_.insert(state_);
    for (const DuplicateId& d : items_.duplicates()) {
      if (!reported_.insert(std::make_tuple(d.window, d.id)).second) continue;
      std::fprintf(stderr, "audit: duplicate widget ID (%s): %s\n", state_.c_str(), d.describe().c_str());
      ++duplicates_;
    }
    lastItems_ = items_.items();
    return true;
  }

  void frameThrew(int index, const std::string& what) override {
    std::fprintf(stderr, "audit: frame %d (%s) threw: %s\n", index, state_.c_str(), what.c_str());
    threw_ = true;
  }

  int exitCode() const override {
    std::printf("audit: %d frames, %zu widget states, %zu distinct widget IDs, %d duplicated\n", frames_,
                states_.size(), ids_.size(), duplicates_);
    std::fflush(stdout);
    return hookMissing_ || threw_ || duplicates_ > 0 ? 1 : 0;
  }

 private:
  void add(const std::string& state, std::function<void(DrivenViewer&)> apply, int frames = 2) {
    queue_.push_back(AuditFrame{state, std::move(apply), {}});
    for (int i = 1; i < frames; ++i) queue_.push_back(AuditFrame{state, nullptr, {}});
  }

  // Each strategy of every integrator type, its light selection (where it takes one) `all`: the
  // states below vary the light selection of those that take one.
  static std::vector<IntegratorDesc> auditedStrategies() {
    std::vector<IntegratorDesc> out;
    for (const IntegratorDesc& d : everyStrategy())
      if (!d.usesLightSelection() || d.lightSelection == LightSelection::All) out.push_back(d);
    return out;
  }

  // Every panel state the scene offers: one frame for each strategy, light selection and sampler (the
  // panels draw the state set before the frame), two for the others (the second sees it settled).
  void planSettings(ViewerController& c) {
    const RenderSettings initial = c.settings();
    for (const IntegratorDesc& s : auditedStrategies()) {
      std::vector<LightSelection> selections;
      if (s.usesLightSelection())
        for (const LightSelectionRow& r : kLightSelections) selections.push_back(r.selection);
      else
        selections.push_back(c.defaultLightSelection());
      for (LightSelection l : selections)
        for (const SamplerRow& sampler : samplerTable()) {
          const std::string state =
              strategyLabel(s) + ", " + std::string(nameOf(l)) + ", " + std::string(sampler.label);
          add(
              state,
              [s, l, kind = sampler.kind](DrivenViewer& v) {
                ViewerController& c = v.controller();
                c.setStrategy(s);
                c.setLightSelection(l);
                RenderSettings r = c.settings();
                r.samplerKind = kind;
                c.setSettings(r);
              },
              1);
        }
      add(strategyLabel(s) + ", time budget", [](DrivenViewer& v) {
        RenderLimits l = v.controller().limits();
        l.seconds = 5, l.targetSpp = 0;
        v.controller().setLimits(l);
      });
      add(strategyLabel(s) + ", target spp", [](DrivenViewer& v) {
        RenderLimits l = v.controller().limits();
        l.seconds = 0, l.targetSpp = 64;
        v.controller().setLimits(l);
      });
      add(strategyLabel(s) + ", compare", [s](DrivenViewer& v) {
        v.controller().setStrategy(s);
        v.controller().setCompare(true);
      });
      queue_.push_back(AuditFrame{"compare choices", [this, s](DrivenViewer& v) { planCompare(v, s); }, {}});
      add(strategyLabel(s) + ", MIS light share", [](DrivenViewer& v) {
        ViewerController& c = v.controller();
        c.setCompare(false);
        if (c.lightShareOffered()) c.setLightShareView(true);
      });
      add(strategyLabel(s) + ", colour view",
          [](DrivenViewer& v) { v.controller().setLightShareView(false); });
    }
    add(
        "help and warp inspector open",
        [initial](DrivenViewer& v) {
          v.controller().setSettings(initial);
          v.setHelpOpen(true);
          v.setWarpInspectorOpen(true);
        },
        3);
  }

  // Each right-side strategy of compare mode, queued at the front when compare mode is on for `s`.
  void planCompare(DrivenViewer& v, const IntegratorDesc& s) {
    ViewerController& c = v.controller();
    std::deque<AuditFrame> frames;
    for (const IntegratorDesc& right : everyStrategyOfType(c.settings().integrator)) {
      if (!c.comparableWithLeft(right)) continue;
      const std::string state = strategyLabel(s) + " | " + strategyLabel(right);
      frames.push_back(
          AuditFrame{state, [right](DrivenViewer& v) { v.controller().setCompareIntegrator(right); }, {}});
      frames.push_back(AuditFrame{state, nullptr, {}});
    }
    frames.push_back(
        AuditFrame{"compare off", [](DrivenViewer& v) { v.controller().setCompare(false); }, {}});
    queue_.insert(queue_.begin(), frames.begin(), frames.end());
  }

  // Clicks every widget of the last frame once, each from the same state (compare mode where
  // offered, help and warp inspector open): a move, a press, a release and a frame to draw what
  // opened (a combo's list, a popup, a tree node, an active text field), then Escape.
  void planClickWalk(DrivenViewer& v) {
    const std::vector<RecordedItem> items = lastItems_;
    const bool compare = v.controller().compareOffered();
    int w = 0, h = 0;
    v.windowSize(w, h);
    for (const RecordedItem& it : items) {
      if (it.id == 0 || it.x1 <= 0 || it.y1 <= 0 || it.x0 >= w || it.y0 >= h) continue;
      const float x = std::min((it.x0 + it.x1) * 0.5f, float(w - 1)),
                  y = std::min((it.y0 + it.y1) * 0.5f, float(h - 1));
      char state[160];
      std::snprintf(state, sizeof state, "after a click at (%.0f, %.0f) in \"%s\"", x, y,
                    items_.windowName(it.window).c_str());
      InputFrame at;
      at.x = x, at.y = y;
      queue_.push_back(AuditFrame{state,
                                  [compare](DrivenViewer& v) {
                                    v.setHelpOpen(true);
                                    v.setWarpInspectorOpen(true);
                                    if (compare && !v.controller().compareEnabled())
                                      v.controller().setCompare(true);
                                  },
                                  at});
      InputFrame down = at;
      down.buttons = 1;
      queue_.push_back(AuditFrame{state, nullptr, down});
      queue_.push_back(AuditFrame{state, nullptr, at});
      queue_.push_back(AuditFrame{state, nullptr, at});
      InputFrame escape = at;
      escape.key = ImGuiKey_Escape;
      queue_.push_back(AuditFrame{state, nullptr, escape});
      queue_.push_back(AuditFrame{state, nullptr, at});
    }
  }

  ItemLog items_;
  std::deque<AuditFrame> queue_;
  std::vector<RecordedItem> lastItems_;
  std::string state_;
  std::set<std::string> states_;
  std::set<std::uint32_t> ids_;
  std::set<std::tuple<std::string, std::uint32_t>> reported_;
  bool walked_ = false, hookMissing_ = false, threw_ = false;
  int frames_ = 0, duplicates_ = 0;
};

}  // namespace

std::shared_ptr<FrameDriver> makeIdAuditDriver() {
  return std::make_shared<IdAuditDriver>();
}

}  // namespace penumbra::ui
