#include "app/ui/convergence_tracker.h"

#include <filesystem>

#include "core/math/error.h"

namespace penumbra::ui {

namespace {

// The scene as currently rendered: the loaded geometry with the live camera and settings.
LoadedScene liveScene(const ViewerController& c) {
  LoadedScene s;
  s.desc = c.liveDesc();
  s.scene = c.scene().scene;
  s.settings = c.settings();
  s.path = c.scene().path;
  return s;
}

}  // namespace

void ConvergenceTracker::rekey(const ViewerController& c) {
  // Scene, camera or settings changes all restart the accumulation, so the (costly: XML + files)
  // content hash is recomputed only on a restart or a new scene.
  if (c.restartCount() == lastRestart_ && c.scene().scene == lastScene_ && !key_.empty()) return;
  lastRestart_ = c.restartCount();
  lastScene_ = c.scene().scene;
  LoadedScene live = liveScene(c);
  std::string key = sceneContentHash(live.desc) + "/" +
                    strategyLabel(referenceEstimator(live.settings.integrator, *live.scene));
  if (key == key_) return;
  key_ = key;
  curves_.clear();  // errors against another reference (camera, scene) are not comparable
  reference_ = Reference();
  mask_.clear();
  userReference_ = false;
  error_.clear();
  cachePath_ = referenceCachePath(live);
  try {
    // 4x4 filter samples per pixel (the CLI uses 16x16): this runs on the UI thread when the camera
    // changes and blocks it (~0.2 s at 128x128 on this machine); still far below the live noise.
    if (hasClosedFormReference(live))
      reference_ = closedFormReference(live, 4);
    else if (std::filesystem::exists(cachePath_))
      reference_ = readReference(cachePath_);
    const auto& cam = live.settings.camera;
    if (!reference_.mean.empty() &&
        (reference_.mean.width != cam.width || reference_.mean.height != cam.height)) {
      error_ = "reference size does not match the camera";
      reference_ = Reference();
    }
    if (!reference_.mean.empty()) mask_ = emitterMask(live);
  } catch (const std::exception& e) {
    error_ = e.what();
    reference_ = Reference();
  }
}

bool ConvergenceTracker::loadReference(const ViewerController& c, const std::string& path) {
  try {
    Reference ref = readReference(path);
    const auto& cam = c.settings().camera;
    if (ref.mean.width != cam.width || ref.mean.height != cam.height)
      throw Error(path + " is " + std::to_string(ref.mean.width) + "x" + std::to_string(ref.mean.height) +
                  ", the camera renders " + std::to_string(cam.width) + "x" + std::to_string(cam.height));
    rekey(c);
    reference_ = std::move(ref);
    reference_.source = "file " + path;
    mask_ = emitterMask(liveScene(c));
    userReference_ = true;
    error_.clear();
    lastVersion_ = 0;
    return true;
  } catch (const std::exception& e) {
    error_ = e.what();
    return false;
  }
}

void ConvergenceTracker::clearCurves() {
  curves_.clear();
}

void ConvergenceTracker::update(const ViewerController& c) {
  rekey(c);
  if (reference_.mean.empty()) return;
  const FilmSnapshot& snap = c.snapshot();
  // The controller reads the last pass of a finished accumulation from the film without a new
  // version, so a change of spp also counts as new.
  if ((snap.version == lastVersion_ && snap.spp == lastSpp_) || snap.spp == 0 || snap.mean.empty()) return;
  if (snap.mean.width != reference_.mean.width || snap.mean.height != reference_.mean.height) return;
  lastVersion_ = snap.version;
  lastSpp_ = snap.spp;
  if (curves_.empty() || curves_.back().restart != c.snapshotRestart()) {
    // Accumulations cut short after a point (e.g. while dragging a slider) would only clutter the plot.
    if (!curves_.empty() && curves_.back().seconds.size() < 2 && curves_.back().spp.back() < 4)
      curves_.pop_back();
    ConvergenceCurve curve;
    curve.label = strategyLabel(c.settings().integrator);
    curve.restart = c.snapshotRestart();
    curves_.push_back(std::move(curve));
    if (curves_.size() > kMaxCurves) curves_.erase(curves_.begin());
  }
  ConvergenceCurve& cur = curves_.back();
  // Keep the curve small: a point per 2% of elapsed time (log-uniform on the plot).
  if (!cur.seconds.empty() && snap.seconds < cur.seconds.back() * 1.02) return;
  latest_ = computeErrors(snap.mean, reference_.mean, reference_.standardError, mask_);
  cur.seconds.push_back(snap.seconds);
  cur.spp.push_back(snap.spp);
  cur.rmse.push_back(latest_.all.rmse);
  cur.rmseNoLight.push_back(latest_.noLight.rmse);
}

}  // namespace penumbra::ui
