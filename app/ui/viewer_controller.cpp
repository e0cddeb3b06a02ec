#include "app/ui/viewer_controller.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "app/ui/reload_rules.h"
#include "app/ui/strategy_choices.h"
#include "app/ui/viewer_output.h"
#include "core/sampling/sampler_table.h"
#include "core/scene/light_selection_default.h"
#include "core/scene/scene_writer.h"
#include "core/scene/xml_parser.h"

namespace penumbra::ui {

namespace fs = std::filesystem;

ViewerController::ViewerController(LoadedScene scene, Overrides overrides, int threads)
    : files_(std::move(overrides)), compare_(threads, signal_) {
  adoptScene(std::move(scene));
  if (!scene_.path.empty()) files_.rememberRecent(scene_.path);
}

ViewerController::~ViewerController() {
  compare_.right().cancel();
  compare_.left().cancel();
}

void ViewerController::adoptScene(LoadedScene loaded) {
  scene_ = std::move(loaded);
  glossy_ = glossyBsdfs(scene_.desc);
  settings_ = scene_.settings;
  limits_.reset(settings_.sampleCount);
  sceneError_.clear();
  files_.watch(scene_.path);
  resetOrbit();
  chooseCompareDefault();
}

void ViewerController::resetOrbit() {
  orbit_.reset(settings_.camera, scene_.settings.camera, scene_.desc, scene_.scene);
}

// ---- rendering --------------------------------------------------------------------------------------

void ViewerController::start() {
  startLeft();
  if (compare_.enabled()) startCompare();
}

void ViewerController::restart() {
  start();
  setPaused(false);
}

void ViewerController::startLeft() {
  if (lightShareView_ && !lightShareOffered()) lightShareView_ = false;
  SessionJob job{scene_.scene, settings_,
                 lightShareView_ ? RenderOutput::MisLightShare : RenderOutput::Radiance};
  samplerNote_ = compare_.startLeft(std::move(job), limits_.limits());
}

void ViewerController::startCompare() {
  compare_.startRight(SessionJob{scene_.scene, settings_, RenderOutput::Radiance}, limits_.limits());
}

void ViewerController::setPaused(bool paused) {
  compare_.setPaused(paused);
}

bool ViewerController::pollSnapshot(bool wantStandardError, bool requestNext) {
  finishLoading();
  const bool changed = compare_.poll(wantStandardError, requestNext);
  if (onSnapshotPolled) onSnapshotPolled(*this);
  return changed;
}

// ---- compare mode -----------------------------------------------------------------------------------

void ViewerController::setCompare(bool on) {
  if (on == compare_.enabled()) return;
  compare_.setEnabled(on);
  start();  // both sides start together with their (new) share of the threads
}

void ViewerController::setCompareIntegrator(const IntegratorDesc& d) {
  if (compare_.setIntegrator(d) && compare_.enabled()) startCompare();
}

bool ViewerController::compareOffered() const {
  return ui::offersCompare(settings_.integrator);
}

bool ViewerController::comparableWithLeft(const IntegratorDesc& d) const {
  return ui::comparable(d, settings_.integrator, sceneHasAreaLights());
}

IntegratorDesc ViewerController::parseCompareStrategy(const std::string& name) const {
  return ui::parseCompareStrategy(name, settings_.integrator, sceneHasAreaLights());
}

IntegratorDesc ViewerController::renderedCompareIntegrator() const {
  return compare_.renderedIntegrator(settings_.integrator, sceneHasAreaLights());
}

// The right side's strategy stays one the scene can render, and differs from the left one when
// another applies.
void ViewerController::chooseCompareDefault() {
  compare_.chooseDefault(settings_.integrator, sceneHasAreaLights());
}

// ---- live settings ----------------------------------------------------------------------------------

static bool sameSettings(const RenderSettings& a, const RenderSettings& b) {
  return a.camera == b.camera && a.filter == b.filter && a.samplerKind == b.samplerKind &&
         a.sampleCount == b.sampleCount && a.seed == b.seed && a.integrator == b.integrator;
}

void ViewerController::setSettings(const RenderSettings& s) {
  if (sameSettings(s, settings_)) return;
  RenderSettings sameIntegrator = s;
  sameIntegrator.integrator = settings_.integrator;
  bool onlyIntegrator = sameSettings(sameIntegrator, settings_);
  // The target spp follows the sampler's sampleCount while the two are equal.
  limits_.followSampleCount(settings_.sampleCount, s.sampleCount);
  const IntegratorDesc oldCompare = renderedCompareIntegrator();
  settings_ = s;
  chooseCompareDefault();  // the left side's type may have changed
  // The right side renders with the left side's counts: a change of either restarts it too.
  if (compare_.enabled() && !(oldCompare == renderedCompareIntegrator())) {
    start();
    return;
  }
  if (compare_.enabled() && onlyIntegrator)
    startLeft();  // the right side renders its own strategy: keep its accumulation
  else
    start();
}

void ViewerController::setLimits(const RenderLimits& l) {
  if (!limits_.set(l)) return;
  // A sampler shaped by the count (stratified, zsobol) needs a new pattern for a new target.
  if (samplerRow(settings_.samplerKind).usesSampleCount()) return start();
  const RenderLimits run = effectiveLimits();
  if (!compare_.left().extend(run)) startLeft();  // a new target continues the accumulation
  if (compare_.enabled() && !compare_.right().extend(run)) startCompare();
}

std::string ViewerController::stopText() const {
  return ui::stopText(effectiveLimits(), limits_.limits(), compare_.enabled());
}

// ---- strategy and light selection -------------------------------------------------------------------

void ViewerController::setStrategy(const IntegratorDesc& axes) {
  RenderSettings s = settings_;
  s.integrator = withCountsOf(axes, s.integrator);
  setSettings(s);
}

std::string ViewerController::strategyUnavailableReason(const IntegratorDesc& choice) const {
  return ui::strategyUnavailableReason(choice, scene_.scene.get());
}

void ViewerController::setLightSelection(LightSelection selection) {
  if (!settings_.integrator.usesLightSelection()) return;
  RenderSettings s = settings_;
  s.integrator.lightSelection = selection;
  setSettings(s);
}

size_t ViewerController::areaLightCount() const {
  return scene_.scene ? scene_.scene->areaLightCount() : 0;
}

LightSelection ViewerController::defaultLightSelection() const {
  return penumbra::defaultLightSelection(areaLightCount());
}

std::string ViewerController::lightSelectionDefaultText() const {
  return ui::lightSelectionDefaultText(areaLightCount());
}

// ---- MIS light share view ---------------------------------------------------------------------------

bool ViewerController::lightShareOffered() const {
  return !compare_.enabled() &&
         offersLightShare(applicableStrategy(settings_.integrator, sceneHasAreaLights()));
}

void ViewerController::setLightShareView(bool on) {
  on = on && lightShareOffered();
  if (on == lightShareView_) return;
  lightShareView_ = on;
  startLeft();
}

DisplaySettings ViewerController::shownDisplay() const {
  DisplaySettings d = display;
  if (snapshotIsLightShare()) d.falseColour = FalseColour::MisLightShare;
  return d;
}

// ---- camera -----------------------------------------------------------------------------------------

void ViewerController::applyCamera(const std::optional<glm::mat4>& toWorld) {
  if (!toWorld) return;
  RenderSettings s = settings_;
  s.camera.toWorld = *toWorld;
  setSettings(s);
}

void ViewerController::orbit(float dx, float dy) {
  applyCamera(orbit_.orbit(settings_.camera, dx, dy));
}

void ViewerController::pan(float dx, float dy) {
  applyCamera(orbit_.pan(settings_.camera, dx, dy));
}

void ViewerController::dolly(float steps) {
  applyCamera(orbit_.dolly(settings_.camera, steps));
}

void ViewerController::setFov(float degrees) {
  RenderSettings s = settings_;
  s.camera.fovDegrees = std::clamp(degrees, 1.f, 179.f);
  setSettings(s);
}

void ViewerController::resetCamera() {
  settings_.camera = scene_.settings.camera;  // the orbit's reset clears the limit note
  resetOrbit();
  start();
}

// ---- scene ------------------------------------------------------------------------------------------

void ViewerController::adoptLoaded(LoadedScene loaded, const std::string& path, double seconds) {
  adoptScene(std::move(loaded));
  files_.rememberRecent(path);
  noteLoadSeconds(seconds);
  // Nothing about the old scene carries over: its pause, its last save's message.
  ++sceneSerial_;
  outputStatus_.clear();
  restart();
}

void ViewerController::noteLoadSeconds(double seconds) {
  loadSeconds_ = seconds;
  char buf[96];
  std::snprintf(buf, sizeof buf, "loaded in %.2f s (parse, meshes, BVH build)", seconds);
  sceneStatus_ = buf;
}

bool ViewerController::openScene(const std::string& path) {
  try {
    double seconds = 0;
    LoadedScene loaded = files_.load(path, seconds);
    adoptLoaded(std::move(loaded), path, seconds);
    return true;
  } catch (const std::exception& e) {
    sceneError_ = e.what();
    return false;
  }
}

void ViewerController::openSceneAsync(const std::string& path) {
  files_.loadAsync(path);
  sceneStatus_ = "loading " + path + " ...";
}

bool ViewerController::finishLoading() {
  if (!files_.loadFinished()) return false;
  const std::string path = files_.loadingPath();
  const double seconds = files_.loadingSeconds();
  try {
    adoptLoaded(files_.takeLoaded(), path, seconds);
  } catch (const std::exception& e) {
    sceneError_ = e.what();
    sceneStatus_.clear();
  }
  return true;
}

std::string ViewerController::windowTitle() const {
  return "Penumbra — " + (scene_.path.empty() ? std::string("built-in scene") : scene_.path);
}

bool ViewerController::reloadScene() {
  if (scene_.path.empty()) {
    sceneError_.clear();
    start();
    return true;
  }
  const std::string path = scene_.path;
  const RenderSettings oldFile = scene_.settings;
  const StopLimits oldLimits = limits_;
  const OrbitCamera oldOrbit = orbit_.state();
  LoadedScene loaded;
  try {
    double seconds = 0;
    loaded = files_.load(path, seconds);
  } catch (const std::exception& e) {
    sceneError_ = e.what();
    files_.watch(path);  // do not retry until the file changes again
    return false;
  }
  ReloadedSettings merged = keepUserChanges(oldFile, settings_, loaded.settings);
  adoptScene(std::move(loaded));
  settings_ = merged.settings;
  if (oldLimits.chosenByUser(oldFile.sampleCount)) {
    limits_ = oldLimits;
    merged.kept.push_back("limits");
  } else {
    limits_.reset(settings_.sampleCount);
  }
  if (std::find(merged.kept.begin(), merged.kept.end(), "camera") != merged.kept.end())
    orbit_.restore(oldOrbit);
  chooseCompareDefault();
  sceneStatus_ = reloadStatus(fs::path(path).filename().string(), merged.kept);
  start();
  return true;
}

bool ViewerController::setBsdfProperty(size_t index, std::string_view name, const std::string& value) {
  LoadedScene rebuilt;
  try {
    SceneNode desc = scene_.desc;
    const std::string what = index < glossy_.size() ? glossy_[index].label : "a glossy bsdf";
    setGlossyBsdfProperty(desc, index, name, value,
                          "the Materials panel (" + what + ": " + std::string(name) + " = " + value + ")");
    rebuilt = buildScene(std::move(desc));
  } catch (const std::exception& e) {
    sceneError_ = e.what();
    return false;
  }
  // Only the world changes: the file's settings, the live ones, the limits and the orbit stay.
  scene_.desc = std::move(rebuilt.desc);
  scene_.scene = std::move(rebuilt.scene);
  scene_.warnings = std::move(rebuilt.warnings);
  glossy_ = glossyBsdfs(scene_.desc);
  sceneError_.clear();
  start();
  return true;
}

bool ViewerController::checkFileChanged() {
  if (!files_.changed()) return false;
  reloadScene();
  return true;
}

// ---- output -----------------------------------------------------------------------------------------

SceneNode ViewerController::liveDesc(const std::string& saveDir) const {
  // A lookat camera is written as its <lookat>: a reload orbits about the same target and up.
  return sceneWithSettings(scene_.desc, settings_, {saveDir, orbit_.lookAt(settings_.camera)});
}

std::string ViewerController::liveSceneXml(const std::string& saveDir) const {
  return writeSceneXml(liveDesc(saveDir));
}

std::string ViewerController::saveImage(const std::string& path) const {
  return saveSnapshotImage(path, snapshot(), snapshotIsLightShare(), settings_, scene_.path,
                           display.exposure);
}

std::string ViewerController::saveSceneAs(const std::string& path) const {
  return saveSceneFile(path, scene_.desc, settings_, orbit_.lookAt(settings_.camera));
}

}  // namespace penumbra::ui
