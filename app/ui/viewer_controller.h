// The viewer's state without any GL or ImGui: the loaded scene, the live RenderSettings, the Engine,
// the display settings, the orbit camera, and the rules for what restarts accumulation. The ImGui
// panels and the GL display (viewer_app.*) sit on top of it; tests drive it directly.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/render/engine.h"
#include "core/scene/scene_builder.h"

namespace penumbra::ui {

enum class Tonemap : int { Srgb = 0, Gamma22 = 1 };
// The user's false-colour choices (Display panel), and MisLightShare: how a light-share film
// (ViewerController::setLightShareView) is shown, never chosen directly.
enum class FalseColour : int { None = 0, RelativeError = 1, BadPixels = 2, MisLightShare = 3 };

// Display-only state: changing it never restarts the engine.
struct DisplaySettings {
  float exposure = 0.f;  // stops
  Tonemap tonemap = Tonemap::Srgb;
  FalseColour falseColour = FalseColour::None;
  float zoom = 1.f;              // screen pixels per image pixel
  float panX = 0.f, panY = 0.f;  // image offset from the centred position, screen pixels
  bool fit = true;               // zoom follows the image area until the user zooms
  float compareDivider = 0.5f;   // compare mode: divider position as a fraction of the image width
};

// Orbit camera state derived from a Nori toWorld (columns: left, up, forward, origin).
struct OrbitCamera {
  Vec3 target{0.f};
  Vec3 worldUp{0, 1, 0};  // the scene's <lookat> up when it has one, else the camera's up
  float distance = 1.f;
  // Lowest elevation (sine of the angle above the plane through the target normal to worldUp) the
  // orbit may reach: the upper hemisphere, or the scene camera's own elevation when that is lower.
  float minElevationSin = 0.f;
  // The scene's horizon plane, fixed while the target pans: through the scene's target, normal to
  // worldUp. Orbit and pan keep the camera at least `minHeight` above it (0, or the scene camera's
  // own height when that is lower), so no move takes it under the floor.
  Vec3 horizonPoint{0.f};
  float minHeight = 0.f;
  bool moved = false;  // the user orbited, panned or dollied since the scene's camera was set
  // The camera is the lookat (origin, target, worldUp): the scene's <lookat>, or an orbit, pan or
  // dolly from one. Save as then writes a <lookat>, so the orbit survives a reload.
  bool isLookAt = false;
};

// What cameraLimitNote() says when a move stopped at the horizon plane, or in front of a surface.
inline constexpr const char* kCameraLimitNotes[2] = {
    "stopped at the scene's horizon: the camera stays above the floor plane",
    "stopped in front of a surface: the camera stays outside the objects"};

// What stops the accumulation: the target spp or the time budget (the Sampler panel's choice).
enum class StopRule { TargetSpp, TimeBudget };

// Nice value of the render threads while the viewer runs (Engine::setWorkerNice): the UI thread and the
// GL rasteriser's threads preempt them for the few ms a frame takes, instead of getting a fair share.
inline constexpr int kViewerWorkerNice = 10;

class ViewerController {
 public:
  using Overrides = std::vector<std::pair<std::string, std::string>>;

  // Takes a loaded scene; `threads` <= 0 uses all cores. Does not start rendering.
  ViewerController(LoadedScene scene, Overrides overrides = {}, int threads = 0);
  ~ViewerController();

  // ---- rendering -------------------------------------------------------------------------------
  void start();  // (re)starts accumulation with the live settings and limits (paused stays paused)
  // The Restart button and key: starts again from 0 spp and resumes a paused accumulation.
  void restart();
  void setPaused(bool paused);
  bool paused() const { return engine_.paused(); }
  RenderProgress progress() const { return engine_.progress(); }
  uint64_t restartCount() const { return restarts_; }
  // What a count-shaped sampler (stratified, zsobol) does with the current target, when it is not
  // simply stratified over it (empty otherwise); the sampler panel shows it.
  const std::string& samplerNote() const { return samplerNote_; }
  Engine& engine() { return engine_; }

  // Called once per UI frame: fetches the newest published snapshot and, with requestNext, asks the
  // engines to publish another (resolving a pass costs the workers time: ask only when one will be
  // shown soon). Returns true when snapshot() changed (the texture must be re-uploaded).
  bool pollSnapshot(bool wantStandardError, bool requestNext = true);
  // The pixel under the cursor (x < 0: none): snapshot().probe carries its statistics, from the next
  // published pass, or at once while the accumulation is paused or finished.
  void setProbePixel(int x, int y);
  const FilmSnapshot& snapshot() const { return snapshot_; }
  // Called at the end of every pollSnapshot (e.g. to stream the image to tev: app/cli/view_command.cpp).
  std::function<void(const ViewerController&)> onSnapshotPolled;
  // Restart counter value the current snapshot belongs to.
  uint64_t snapshotRestart() const { return snapshotRestart_; }
  // Count of changes of snapshot() / compareSnapshot() (each side is tone mapped only when it changed).
  uint64_t snapshotSerial() const { return snapshotSerial_; }
  uint64_t compareSnapshotSerial() const { return compareSnapshotSerial_; }
  // True while an accumulation is running (not finished, not paused).
  bool rendering() const;
  // Notified whenever either engine publishes a snapshot or stops (the UI sleeps on it).
  const PublishSignal& publishSignal() const { return *signal_; }

  // ---- compare mode ----------------------------------------------------------------------------
  // A second Engine renders the same scene, camera and sampler with `compareIntegrator()`; the image
  // shows it right of the divider. While it is on, each engine gets half of the threads (at least
  // one), so both strategies get equal shares of time. Enabling or disabling restarts both sides;
  // changing only the left integrator restarts only the left side, and setCompareIntegrator only
  // the right side.
  void setCompare(bool on);
  bool compareEnabled() const { return compare_; }
  const IntegratorDesc& compareIntegrator() const { return compareIntegrator_; }
  void setCompareIntegrator(const IntegratorDesc& d);
  // What the right side may render: the strategies of the left side's integrator type that have
  // shading samples and apply to the scene (strategy table), in table order.
  std::vector<Strategy> compareChoices() const;
  // `--compare NAME`: one of compareChoices() by its short name or label; throws penumbra::Error
  // naming the accepted values.
  IntegratorDesc parseCompareStrategy(const std::string& name) const;
  // What the right side renders: compareIntegrator(), or its fallback when the scene lacks what it
  // needs (strategy table).
  IntegratorDesc renderedCompareIntegrator() const;
  RenderProgress compareProgress() const { return compareEngine_.progress(); }
  const FilmSnapshot& compareSnapshot() const { return compareSnapshot_; }
  uint64_t compareRestartCount() const { return compareRestarts_; }
  Engine& compareEngine() { return compareEngine_; }
  // Threads per engine in the current mode.
  int engineThreads() const;
  // Compare mode is equal-time: unless the user chose a time budget, both sides render for this
  // many seconds (each with half of the threads), not to an spp count.
  static constexpr double kCompareSeconds = 10.0;
  // The limits the engines run with: limits(), or the shared time budget in compare mode.
  RenderLimits effectiveLimits() const;

  // ---- live settings (any change restarts accumulation; geometry is never rebuilt) -------------
  const RenderSettings& settings() const { return settings_; }
  // Replaces the live settings; restarts only if they differ from the current ones.
  void setSettings(const RenderSettings& s);
  const RenderLimits& limits() const { return limits_; }
  void setLimits(const RenderLimits& l);
  // Raising the sampler's sampleCount also raises the target spp while the target equals it (the
  // stratified sampler's strata and the accumulation's end stay tied); this says which stops the
  // render, e.g. "stops at 64 spp (target spp)" or "stops after 10.0 s (time budget, equal time)".
  std::string stopText() const;
  // Switching the rule brings back the value it had (the scene's sampleCount and kDefaultSeconds
  // until the user chose others), so going to the time budget and back keeps the target spp.
  StopRule stopRule() const { return limits_.seconds > 0 ? StopRule::TimeBudget : StopRule::TargetSpp; }
  void setStopRule(StopRule rule);
  void setTargetSpp(uint32_t spp);     // 0: never stop; switches to StopRule::TargetSpp
  void setTimeBudget(double seconds);  // > 0; switches to StopRule::TimeBudget
  uint32_t chosenTargetSpp() const { return chosenTargetSpp_; }
  double chosenSeconds() const { return chosenSeconds_; }
  static constexpr double kDefaultSeconds = 10.0;

  // ---- strategy and light selection ------------------------------------------------------------
  // The strategy list: every row that is its own all-lights row (the rows of one light-sampling
  // measure that differ only in lightSelection appear once, as their `all` row).
  std::vector<Strategy> strategyChoices() const;
  // Switches to one of strategyChoices(), keeping the live light selection where both take one (a
  // strategy that takes none hands over to the scene's default). Restarts when it changed.
  void setStrategy(Strategy choice);
  // Why `s` cannot light this scene, for its greyed-out entry in the list ("" when it can): a
  // strategy that needs area lights on a scene without them ("needs area lights (renders
  // direct/cosine-hemisphere here)"), simple without point or directional lights, the hemisphere
  // strategies on a scene without lights.
  std::string strategyUnavailableReason(Strategy s) const;
  // Whether the live strategy takes a light selection (the panel shows its control only then).
  bool takesLightSelection() const;
  // Switches the live strategy to the row of its measure with `selection`; ignored where it has none.
  void setLightSelection(LightSelection selection);
  // The scene's sphere lights, and the selection the scene builder picks for them when the scene
  // names none (core/scene/light_selection_default.h).
  size_t sphereLightCount() const;
  LightSelection defaultLightSelection() const;
  // "default for 64 sphere lights: bvh (all up to 8)", for the panel.
  std::string lightSelectionDefaultText() const;

  // ---- MIS light share view --------------------------------------------------------------------
  // The "MIS light share" view renders the strategy's light-share output (RenderOutput::MisLightShare:
  // per pixel, the luminance of the light-sampling and of the cosine-hemisphere part of the MIS
  // estimate) and shows the light technique's share as a false-colour map. Offered while the rendered
  // strategy is a mis row (strategy table: offersLightShare) and compare mode is off; a change that
  // stops offering it (another strategy, compare on, a scene without area lights) turns it off.
  // Switching it restarts the accumulation.
  bool lightShareOffered() const;
  void setLightShareView(bool on);
  bool lightShareView() const { return lightShareView_; }
  // Whether snapshot() holds a light-share film (it lags the switch until the new accumulation's
  // first snapshot arrives).
  bool snapshotIsLightShare() const { return snapshotOutput_ == RenderOutput::MisLightShare; }
  // `display` as the image must be shown: its false colour replaced by MisLightShare for a light-share
  // snapshot.
  DisplaySettings shownDisplay() const;

  // ---- camera ----------------------------------------------------------------------------------
  // Orbit, pan and dolly keep the orbit's limits: never under the scene's horizon plane (see
  // OrbitCamera), and pan and dolly stop in front of the first surface on the way (a camera inside
  // an object sees black). cameraLimitNote() says when a move was stopped.
  void orbit(float dxPixels, float dyPixels);
  void pan(float dxPixels, float dyPixels);
  void dolly(float wheelSteps);
  const std::string& cameraLimitNote() const { return cameraLimitNote_; }
  void setFov(float degrees);
  void resetCamera();
  const OrbitCamera& orbitCamera() const { return orbit_; }
  // The target the Camera panel shows: the scene's <lookat> target until the user moves the camera.
  Vec3 shownTarget() const { return orbit_.target; }

  // ---- display (never restarts) ----------------------------------------------------------------
  DisplaySettings display;

  // ---- scene -----------------------------------------------------------------------------------
  const LoadedScene& scene() const { return scene_; }
  // Loads a scene file; on failure keeps the current scene rendering, stores the error text
  // (file:line: ...) in sceneError() and returns false.
  bool openScene(const std::string& path);
  // Loads on a thread (a large mesh's BVH takes seconds); the current scene keeps its image (shown
  // dimmed) until pollSnapshot adopts the new one. Errors land in sceneError() as with openScene.
  void openSceneAsync(const std::string& path);
  bool loading() const { return loading_.valid(); }
  const std::string& loadingPath() const { return loadingPath_; }
  // Adopts a finished asynchronous load (pollSnapshot calls it); true when one finished.
  bool finishLoading();
  // Wall time of the current scene's load: parsing, meshes and the BVH build.
  double loadSeconds() const { return loadSeconds_; }
  // Seconds the calling (UI) thread has spent loading scenes in all: openScene, reloadScene, and
  // openSceneAsync waiting for the previous load. The monkey test's frame-time check leaves it out.
  double blockingLoadSeconds() const { return blockingLoadSeconds_; }
  // For a scene loaded before the controller existed (the command line's): shown as for openScene.
  void noteLoadSeconds(double seconds);
  // Reloads the same file, keeping the live settings the user changed (camera, integrator, sampler,
  // limits) unless the file changed the same setting; sceneStatus() says what was kept.
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
  const std::vector<std::string>& recentFiles() const { return recent_; }
  // .xml files in the current scene's directory.
  std::vector<std::string> siblingScenes() const;
  bool sceneHasAreaLights() const { return scene_.scene && scene_.scene->hasAreaLights(); }

  // ---- output ----------------------------------------------------------------------------------
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
  double secondsSinceRestart() const;

 private:
  void adoptScene(LoadedScene loaded);
  void initOrbitFromCamera();
  void startLeft();
  void startCompare();
  void applyOrbit(const Vec3& origin);
  void moveCamera(const Vec3& origin, const Vec3& target);
  float clearDistance(const Vec3& from, const Vec3& direction, float wanted) const;
  std::filesystem::file_time_type mtimeOf(const std::string& path) const;
  void rememberRecent(const std::string& path);
  void chooseCompareDefault();
  void adoptLoaded(LoadedScene loaded, const std::string& path, double seconds);

  LoadedScene scene_;
  Overrides overrides_;
  int threads_;
  RenderSettings settings_;
  RenderLimits limits_;
  uint32_t chosenTargetSpp_ = 0;            // the target spp while the time budget rules
  double chosenSeconds_ = kDefaultSeconds;  // the time budget while the target spp rules
  std::string cameraLimitNote_;
  std::string outputStatus_;
  uint64_t sceneSerial_ = 0;
  std::chrono::steady_clock::time_point restartTime_{};
  OrbitCamera orbit_;
  std::shared_ptr<PublishSignal> signal_ = std::make_shared<PublishSignal>();
  Engine engine_;
  int probeX_ = -1, probeY_ = -1;  // setProbePixel
  FilmSnapshot snapshot_;
  uint64_t restarts_ = 0;
  std::string samplerNote_;
  uint64_t snapshotRestart_ = 0;
  uint64_t snapshotSerial_ = 0, compareSnapshotSerial_ = 0;
  bool lightShareView_ = false;
  RenderOutput leftOutput_ = RenderOutput::Radiance;      // of the left engine's current job
  RenderOutput snapshotOutput_ = RenderOutput::Radiance;  // of the job snapshot_ came from
  bool compare_ = false;
  IntegratorDesc compareIntegrator_{Strategy::DirectSolidAngle, 1};
  bool compareUserChosen_ = false;  // setCompareIntegrator was called: keep it while it applies
  Engine compareEngine_;
  FilmSnapshot compareSnapshot_;
  uint64_t compareRestarts_ = 0;
  std::string sceneError_;
  std::string sceneStatus_;
  std::future<LoadedScene> loading_;
  std::string loadingPath_;
  std::chrono::steady_clock::time_point loadStart_{};
  double loadSeconds_ = 0;
  double blockingLoadSeconds_ = 0;
  std::vector<std::string> recent_;
  std::filesystem::file_time_type sceneMtime_{};
  std::chrono::steady_clock::time_point lastMtimeCheck_{};
};

// Nori lookAt: columns (left, up, forward, origin).
glm::mat4 lookAt(const Vec3& origin, const Vec3& target, const Vec3& up);

}  // namespace penumbra::ui
