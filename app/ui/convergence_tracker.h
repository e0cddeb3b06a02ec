// The viewer's live error measurement, without GL or ImGui: holds a reference for the
// current scene and camera (closed form for scenes/analytic, the cached reference that
// `penumbra render --reference` writes, or a file the user loads), and turns every new snapshot of the
// accumulation into a point (seconds, RMSE). Each accumulation (restart) is one curve; curves of
// strategies tried earlier are kept so they can be compared side by side (until the
// scene or camera changes: errors against another reference are not comparable).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/ui/viewer_controller.h"
#include "core/analysis/error_metrics.h"
#include "core/analysis/reference.h"

namespace penumbra::ui {

struct ConvergenceCurve {
  std::string label;  // strategy label, e.g. "direct/area"
  uint64_t restart = 0;
  std::vector<double> seconds, rmse, rmseNoLight;
  std::vector<uint32_t> spp;
};

class ConvergenceTracker {
 public:
  static constexpr std::size_t kMaxCurves = 12;

  // Call once per frame after ViewerController::pollSnapshot. Re-keys the reference when the scene
  // content or the camera changed (looking for the closed form / cached reference again), then adds a
  // point for a new snapshot. Cheap when nothing changed.
  void update(const ViewerController& c);
  // Loads a user reference (EXR/PFM, sibling .stderr.exr used if present). Returns false and sets
  // error() on failure (wrong size, unreadable).
  bool loadReference(const ViewerController& c, const std::string& path);
  void clearCurves();

  bool hasReference() const { return !reference_.mean.empty(); }
  const Reference& reference() const { return reference_; }
  const std::vector<ConvergenceCurve>& curves() const { return curves_; }
  const std::string& error() const { return error_; }
  const std::string& cachePath() const { return cachePath_; }
  // The last metrics computed (for the current accumulation).
  const ErrorReport& latest() const { return latest_; }

 private:
  void rekey(const ViewerController& c);

  std::string key_;  // scene content hash + camera, the reference's validity
  std::string cachePath_;
  Reference reference_;
  std::vector<uint8_t> mask_;
  std::vector<ConvergenceCurve> curves_;
  uint64_t lastVersion_ = 0;
  uint32_t lastSpp_ = 0;
  ErrorReport latest_;
  std::string error_;
  bool userReference_ = false;
  uint64_t lastRestart_ = ~0ull;
  std::shared_ptr<const Scene> lastScene_;
};

}  // namespace penumbra::ui
