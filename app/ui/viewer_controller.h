// The viewer's state without any GL or ImGui, as one façade the panels, the frame loop and the tests
// use: the loaded scene, the live RenderSettings and limits, the display settings, and the rules for
// what restarts accumulation. The parts it composes, one file each: EngineSession (one engine and its
// snapshots) and CompareMode (two of them at equal time), OrbitControl (the orbit camera),
// SceneFiles (loading and watching) with reload_rules, StopLimits (target spp or time budget),
// strategy_choices (what the strategy list offers) and viewer_output (saving images and scenes, with
// core/scene/scene_writer for the XML).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/ui/compare_mode.h"
#include "app/ui/display_settings.h"
#include "app/ui/engine_session.h"
#include "app/ui/orbit_camera.h"
#include "app/ui/scene_files.h"
#include "app/ui/stop_rule.h"
#include "core/render/engine.h"
#include "core/scene/glossy_bsdfs.h"
#include "core/scene/scene_builder.h"

namespace penumbra::ui {

class ViewerController {
 public:
  using Overrides = SceneFiles::Overrides;

  // Takes a loaded scene; `threads` <= 0 uses all cores. Does not start rendering.
  ViewerController(LoadedScene scene, Overrides overrides = {}, int threads = 0);
  ~ViewerController();

  // ---- rendering -------------------------------------------------------------------------------
  void start();  // (re)starts accumulation with the live settings and limits (paused stays paused)
  // The Restart button and key: starts again from 0 spp and resumes a paused accumulation.
  void restart();
  void setPaused(bool paused);
  bool paused() const { return compare_.left().paused(); }
  RenderProgress progress() const { return compare_.left().progress(); }
  uint64_t restartCount() const { return compare_.left().restarts(); }
  // What a count-shaped sampler (stratified, zsobol) does with the current target, when it is not
  // simply stratified over it (empty otherwise); the sampler panel shows it.
  const std::string& samplerNote() const { return samplerNote_; }
  Engine& engine() { return compare_.left().engine(); }

  // Called once per UI frame: adopts a finished asynchronous load, fetches the newest published
  // snapshot and, with requestNext, asks the engines to publish another (resolving a pass costs the
  // workers time: ask only when one will be shown soon). Returns true when snapshot() changed (the
  // texture must be re-uploaded).
  bool pollSnapshot(bool wantStandardError, bool requestNext = true);
  // The pixel under the cursor (x < 0: none): snapshot().probe carries its statistics, from the next
  // published pass, or at once while the accumulation is paused or finished.
  void setProbePixel(int x, int y) { compare_.left().setProbePixel(x, y); }
  const FilmSnapshot& snapshot() const { return compare_.left().snapshot(); }
  // Called at the end of every pollSnapshot (e.g. to stream the image to tev: app/cli/view_command.cpp).
  std::function<void(const ViewerController&)> onSnapshotPolled;
  // Restart counter value the current snapshot belongs to.
  uint64_t snapshotRestart() const { return compare_.left().snapshotRestart(); }
  // Count of changes of snapshot() / compareSnapshot() (each side is tone mapped only when it changed).
  uint64_t snapshotSerial() const { return compare_.left().snapshotSerial(); }
  uint64_t compareSnapshotSerial() const { return compare_.right().snapshotSerial(); }
  // True while an accumulation is running (not finished, not paused).
  bool rendering() const { return compare_.busy(); }
  // Notified whenever either engine publishes a snapshot or stops (the UI sleeps on it).
  const PublishSignal& publishSignal() const { return *signal_; }

  // ---- compare mode (compare_mode.h) -----------------------------------------------------------
  // Enabling or disabling restarts both sides; changing only the left integrator restarts only the
  // left side, and setCompareIntegrator only the right side.
  void setCompare(bool on);
  bool compareEnabled() const { return compare_.enabled(); }
  const IntegratorDesc& compareIntegrator() const { return compare_.integrator(); }
  void setCompareIntegrator(const IntegratorDesc& d);
  // Whether the left side's integrator type has other strategies to compare with (direct, ao).
  bool compareOffered() const;
  // Whether `d` may be the right side's strategy: the left side's type, applicable to the scene.
  bool comparableWithLeft(const IntegratorDesc& d) const;
  // `--compare NAME` (strategy_choices.h: parseCompareStrategy); throws penumbra::Error naming the
  // accepted values.
  IntegratorDesc parseCompareStrategy(const std::string& name) const;
  // What the right side renders: compareIntegrator() with the left side's counts, or its fallback
  // when the scene lacks what it needs.
  IntegratorDesc renderedCompareIntegrator() const;
  RenderProgress compareProgress() const { return compare_.right().progress(); }
  const FilmSnapshot& compareSnapshot() const { return compare_.right().snapshot(); }
  uint64_t compareRestartCount() const { return compare_.right().restarts(); }
  Engine& compareEngine() { return compare_.right().engine(); }
  // Threads per engine in the current mode.
  int engineThreads() const { return compare_.engineThreads(); }
  // Compare mode is equal-time: unless the user chose a time budget, both sides render for this
  // many seconds (each with half of the threads), not to an spp count.
  static constexpr double kCompareSeconds = CompareMode::kSeconds;
  // The limits the engines run with: limits(), or the shared time budget in compare mode.
  RenderLimits effectiveLimits() const { return compare_.effectiveLimits(limits_.limits()); }

  // ---- live settings (any change restarts accumulation; geometry is never rebuilt) -------------
  const RenderSettings& settings() const { return settings_; }
  // Replaces the live settings; restarts only if they differ from the current ones.
  void setSettings(const RenderSettings& s);
  const RenderLimits& limits() const { return limits_.limits(); }
  void setLimits(const RenderLimits& l);
  // Raising the sampler's sampleCount also raises the target spp while the target equals it (the
  // stratified sampler's strata and the accumulation's end stay tied); this says which stops the
  // render, e.g. "stops at 64 spp (target spp)" or "stops after 10.0 s (time budget, equal time)".
  std::string stopText() const;
  // Switching the rule brings back the value it had (the scene's sampleCount and kDefaultSeconds
  // until the user chose others), so going to the time budget and back keeps the target spp.
  StopRule stopRule() const { return limits_.rule(); }
  void setStopRule(StopRule rule) { setLimits(limits_.forRule(rule)); }
  void setTargetSpp(uint32_t spp) { setLimits(limits_.withTargetSpp(spp)); }          // 0: never stop
  void setTimeBudget(double seconds) { setLimits(limits_.withTimeBudget(seconds)); }  // > 0
  uint32_t chosenTargetSpp() const { return limits_.chosenTargetSpp(); }
  double chosenSeconds() const { return limits_.chosenSeconds(); }
  static constexpr double kDefaultSeconds = StopLimits::kDefaultSeconds;

  // ---- strategy axes (strategy_choices.h) ------------------------------------------------------
  // Switches to the type and every axis of `axes`, keeping the live counts. Restarts when it changed.
  void setStrategy(const IntegratorDesc& axes);
  // Why `s` cannot light this scene, for its greyed-out entry ("" when it can).
  std::string strategyUnavailableReason(const IntegratorDesc& s) const;
  // Switches the live light selection; ignored where the live strategy takes none.
  void setLightSelection(LightSelection selection);
  // The scene's area lights, and the selection the scene builder picks for them when the scene
  // names none (core/scene/light_selection_default.h).
  size_t areaLightCount() const;
  LightSelection defaultLightSelection() const;
  // "default for 300 area lights: bvh (all up to 256)", for the panel.
  std::string lightSelectionDefaultText() const;

  // ---- MIS light share view --------------------------------------------------------------------
  // The "MIS light share" view renders the strategy's light-share output (RenderOutput::MisLightShare:
  // per pixel, the luminance of the light-sampling and of the cosine-hemisphere part of the MIS
  // estimate) and shows the light technique's share as a false-colour map. Offered while the rendered
  // strategy is MIS (offersLightShare) and compare mode is off; a change that
  // stops offering it (another strategy, compare on, a scene without area lights) turns it off.
  // Switching it restarts the accumulation.
  bool lightShareOffered() const;
  void setLightShareView(bool on);
  bool lightShareView() const { return lightShareView_; }
  // Whether snapshot() holds a light-share film (it lags the switch until the new accumulation's
  // first snapshot arrives).
  bool snapshotIsLightShare() const {
    return compare_.left().snapshotOutput() == RenderOutput::MisLightShare;
  }
  // `display` as the image must be shown: its false colour replaced by MisLightShare for a light-share
  // snapshot.
  DisplaySettings shownDisplay() const;

  // ---- camera (orbit_camera.h) -----------------------------------------------------------------
  // Each move restarts the accumulation; cameraLimitNote() says when one was stopped at a limit.
  void orbit(float dxPixels, float dyPixels);
  void pan(float dxPixels, float dyPixels);
  void dolly(float wheelSteps);
  const std::string& cameraLimitNote() const { return orbit_.limitNote(); }
  void setFov(float degrees);
  void resetCamera();
  const OrbitCamera& orbitCamera() const { return orbit_.state(); }
  // The target the Camera panel shows: the scene's <lookat> target until the user moves the camera.
  Vec3 shownTarget() const { return orbit_.state().target; }

  // ---- display (never restarts) ----------------------------------------------------------------
  DisplaySettings display;

  // ---- scene (scene_files.h) -------------------------------------------------------------------
  const LoadedScene& scene() const { return scene_; }
  // Loads a scene file; on failure keeps the current scene rendering, stores the error text
  // (file:line: ...) in sceneError() and returns false.
  bool openScene(const std::string& path);
  // Loads on a thread (a large mesh's BVH takes seconds); the current scene keeps its image (shown
  // dimmed) until pollSnapshot adopts the new one. Errors land in sceneError() as with openScene.
  void openSceneAsync(const std::string& path);
  bool loading() const { return files_.loading(); }
  const std::string& loadingPath() const { return files_.loadingPath(); }
  // Adopts a finished asynchronous load (pollSnapshot calls it); true when one finished.
  bool finishLoading();
  // Wall time of the current scene's load: parsing, meshes and the BVH build.
  double loadSeconds() const { return loadSeconds_; }
  // Seconds the calling (UI) thread has spent loading scenes in all: openScene, reloadScene, and
  // openSceneAsync waiting for the previous load. The monkey test's frame-time check leaves it out.
  double blockingLoadSeconds() const { return files_.blockingSeconds(); }
  // For a scene loaded before the controller existed (the command line's): shown as for openScene.
  void noteLoadSeconds(double seconds);
  // Reloads the same file, keeping the live settings the user changed (camera, integrator, sampler,
  // limits) unless the file changed the same setting (reload_rules.h); sceneStatus() says what was
  // kept.
  bool reloadScene();
  const std::string& sceneStatus() const { return sceneStatus_; }
  // "Penumbra — <scene file>": the window title, following the open scene.
  std::string windowTitle() const;
  // Reloads when the scene file's modification time changed (checked at most twice a second).
  bool checkFileChanged();
  const std::string& sceneError() const { return sceneError_; }
  // Counts the scenes adopted (opened, dropped, loaded; not reloads): state about the old scene —
  // the pause, the last save's message, the fields' notes — ends with it.
  uint64_t sceneSerial() const { return sceneSerial_; }
  const std::vector<std::string>& recentFiles() const { return files_.recent(); }
  // .xml files in the current scene's directory.
  std::vector<std::string> siblingScenes() const { return ui::siblingScenes(scene_.path); }
  bool sceneHasAreaLights() const { return scene_.scene && scene_.scene->hasAreaLights(); }
  // The scene's glossy BSDFs (the Materials panel), and an edit of one: property `name` of entry
  // `index` set to the text `value`, the scene built again from its description with everything the
  // user set kept (camera, settings, limits), and the render restarted. A value the scene file would
  // be refused for is refused alike: sceneError() says why and the last good scene goes on. Edits
  // last until the file is reloaded; Save as writes them.
  const std::vector<GlossyBsdfEntry>& glossyBsdfEntries() const { return glossy_; }
  bool setBsdfProperty(size_t index, std::string_view name, const std::string& value);

  // ---- output (viewer_output.h) ----------------------------------------------------------------
  // The scene description with the live settings written into it, as XML (core/scene/scene_writer.h;
  // the camera as a <lookat> while it is the orbit's lookat). With `saveDir`, relative file paths
  // (meshes) are rewritten to resolve from that directory: relative when the two share a root,
  // absolute otherwise.
  SceneNode liveDesc(const std::string& saveDir = "") const;
  std::string liveSceneXml(const std::string& saveDir = "") const;
  // PNG of the display (current exposure, sRGB), EXR/PFM of the accumulation, scene XML; all atomic.
  // Return a status message; throw penumbra::Error on failure.
  std::string saveImage(const std::string& path) const;
  std::string saveSceneAs(const std::string& path) const;
  // The last save's message (or error), shown under the save fields until another scene opens.
  const std::string& outputStatus() const { return outputStatus_; }
  void setOutputStatus(std::string status) { outputStatus_ = std::move(status); }

  // Seconds since the left side's accumulation last (re)started: the viewer dims an image left over
  // from before the change once its replacement is late.
  double secondsSinceRestart() const { return compare_.left().secondsSinceStart(); }

 private:
  void adoptScene(LoadedScene loaded);
  void adoptLoaded(LoadedScene loaded, const std::string& path, double seconds);
  void resetOrbit();
  void startLeft();
  void startCompare();
  void chooseCompareDefault();
  void applyCamera(const std::optional<glm::mat4>& toWorld);

  LoadedScene scene_;
  std::vector<GlossyBsdfEntry> glossy_;  // glossyBsdfs(scene_.desc)
  RenderSettings settings_;
  StopLimits limits_;
  bool lightShareView_ = false;
  std::string samplerNote_;
  std::string outputStatus_;
  std::string sceneError_;
  std::string sceneStatus_;
  uint64_t sceneSerial_ = 0;
  double loadSeconds_ = 0;
  OrbitControl orbit_;
  SceneFiles files_;
  std::shared_ptr<PublishSignal> signal_ = std::make_shared<PublishSignal>();
  CompareMode compare_;  // the engines: declared last, so they stop before the rest goes
};

}  // namespace penumbra::ui
