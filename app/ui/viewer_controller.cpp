#include "app/ui/viewer_controller.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

#include "app/ui/light_share_map.h"
#include "core/image/atomic_file.h"
#include "core/image/image_io.h"
#include "core/math/error.h"
#include "core/math/frame.h"
#include "core/render/light_selection_rows.h"
#include "core/render/sample_count_fit.h"
#include "core/sampling/sampler_table.h"
#include "core/scene/light_selection_default.h"
#include "core/scene/scene_writer.h"
#include "core/scene/xml_parser.h"

namespace penumbra::ui {

namespace fs = std::filesystem;

glm::mat4 lookAt(const Vec3& origin, const Vec3& target, const Vec3& up) {
  Vec3 dir = glm::normalize(target - origin);
  Vec3 left = glm::cross(up, dir);
  if (glm::length(left) < 1e-6f)
    left = glm::cross(std::abs(dir.z) < 0.9f ? Vec3(0, 0, 1) : Vec3(1, 0, 0), dir);
  left = glm::normalize(left);
  Vec3 newUp = glm::normalize(glm::cross(dir, left));
  return cameraToWorld(origin, left, newUp, dir);
}

ViewerController::ViewerController(LoadedScene scene, Overrides overrides, int threads)
    : overrides_(std::move(overrides)), threads_(threads) {
  for (Engine* e : {&engine_, &compareEngine_}) {
    e->setWorkerNice(kViewerWorkerNice);
    e->setPublishSignal(signal_);
  }
  adoptScene(std::move(scene));
  if (!scene_.path.empty()) rememberRecent(scene_.path);
}

ViewerController::~ViewerController() {
  if (loading_.valid()) loading_.wait();  // the loader thread reads nothing of ours, but must end
  compareEngine_.cancel();
  engine_.cancel();
}

void ViewerController::adoptScene(LoadedScene loaded) {
  scene_ = std::move(loaded);
  settings_ = scene_.settings;
  limits_ = RenderLimits{};
  limits_.targetSpp = settings_.sampleCount;
  chosenTargetSpp_ = settings_.sampleCount;
  chosenSeconds_ = kDefaultSeconds;
  sceneError_.clear();
  sceneMtime_ = scene_.path.empty() ? fs::file_time_type{} : mtimeOf(scene_.path);
  initOrbitFromCamera();
  chooseCompareDefault();
}

namespace {
// Equal up to float rounding of the same construction (a lookat rebuilt from its parts).
bool matricesClose(const glm::mat4& a, const glm::mat4& b) {
  float scale = 1.f;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) scale = std::max(scale, std::abs(b[c][r]));
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!(std::abs(a[c][r] - b[c][r]) <= 1e-5f * scale)) return false;
  return true;
}

// The scene camera's toWorld property, when it was written with <lookat>.
const Property* cameraLookAt(const SceneNode& desc) {
  const SceneNode* cam = desc.child("camera");
  if (!cam) return nullptr;
  for (const Property& p : cam->props.properties())
    if (p.name == "toWorld" && p.type == PropertyType::Transform && p.hasLookAt && !p.fromOverride) return &p;
  return nullptr;
}
}  // namespace

void ViewerController::initOrbitFromCamera() {
  const glm::mat4& m = settings_.camera.toWorld;
  Vec3 origin(m[3]), forward = glm::normalize(Vec3(m[2]));
  orbit_.worldUp = glm::normalize(Vec3(m[1]));
  orbit_.moved = false;
  orbit_.isLookAt = false;
  cameraLimitNote_.clear();
  // The horizon plane through the target: the camera stays above it, or at its own height if lower.
  auto setHorizon = [&] {
    orbit_.horizonPoint = orbit_.target;
    orbit_.minHeight = std::min(0.f, glm::dot(origin - orbit_.target, orbit_.worldUp));
  };
  // The scene names its target: orbit about exactly that point (the camera is the file's).
  const Property* look = cameraLookAt(scene_.desc);
  if (look && settings_.camera.toWorld == scene_.settings.camera.toWorld &&
      glm::length(look->lookAtTarget - origin) > 1e-6f && glm::length(look->lookAtUp) > 1e-6f) {
    orbit_.target = look->lookAtTarget;
    orbit_.distance = glm::length(look->lookAtTarget - origin);
    Vec3 up = glm::normalize(look->lookAtUp);
    if (std::abs(glm::dot(up, forward)) < 0.999f) orbit_.worldUp = up;
    orbit_.minElevationSin = std::min(0.f, glm::dot(glm::normalize(origin - orbit_.target), orbit_.worldUp));
    // The camera is exactly the lookat about that target (no transform after the <lookat>).
    orbit_.isLookAt = matricesClose(lookAt(origin, orbit_.target, orbit_.worldUp), m);
    setHorizon();
    return;
  }
  float distance = 0.f;
  if (scene_.scene) {
    Bounds b = scene_.scene->geometry.bounds();
    if (!b.empty()) distance = glm::dot(b.center() - origin, forward);
    // A huge ground plane moves the centre far away: prefer the distance to the nearest object
    // centre-ish point when the bound is unreasonable.
    if (!(distance > 1e-3f) || distance > 10.f * glm::length(origin - b.center()) + 1.f)
      distance = glm::length(b.center() - origin);
  }
  if (!(distance > 1e-3f) || !std::isfinite(distance)) distance = 1.f;
  orbit_.distance = distance;
  orbit_.target = origin + forward * distance;
  orbit_.minElevationSin = std::min(0.f, glm::dot(-forward, orbit_.worldUp));
  setHorizon();
}

int ViewerController::engineThreads() const {
  if (!compare_) return threads_;
  int all = threads_ > 0 ? threads_ : int(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, all / 2);
}

void ViewerController::start() {
  startLeft();
  if (compare_) startCompare();
}

void ViewerController::restart() {
  start();
  setPaused(false);
}

RenderLimits ViewerController::effectiveLimits() const {
  RenderLimits l = limits_;
  if (compare_ && !(l.seconds > 0)) {
    l.targetSpp = 0;
    l.seconds = kCompareSeconds;
  }
  return l;
}

std::string ViewerController::stopText() const {
  RenderLimits l = effectiveLimits();
  char buf[160];
  if (l.seconds > 0)
    std::snprintf(buf, sizeof buf, "stops after %.1f s (%s)", l.seconds,
                  compare_
                      ? (limits_.seconds > 0 ? "time budget, both sides" : "compare: equal time, both sides")
                      : "time budget");
  else if (l.targetSpp > 0)
    std::snprintf(buf, sizeof buf, "stops at %u spp (target spp)", l.targetSpp);
  else
    std::snprintf(buf, sizeof buf, "renders until paused (target spp 0: endless)");
  return buf;
}
void ViewerController::startLeft() {
  auto job = std::make_shared<RenderJob>();
  job->scene = scene_.scene;
  job->settings = settings_;
  if (lightShareView_ && !lightShareOffered()) lightShareView_ = false;
  job->output = lightShareView_ ? RenderOutput::MisLightShare : RenderOutput::Radiance;
  leftOutput_ = job->output;
  bool wasPaused = engine_.paused();
  RenderLimits limits = effectiveLimits();
  // Compare runs at equal time: the final count is then unknown too.
  samplerNote_ = fitSampleCountToTarget(job->settings, limits.seconds > 0 ? 0 : limits.targetSpp);
  limits.preview = true;  // a coarse first frame within milliseconds of any change
  engine_.start(std::move(job), limits, engineThreads());
  if (wasPaused) engine_.setPaused(true);
  ++restarts_;
  restartTime_ = std::chrono::steady_clock::now();
}

void ViewerController::startCompare() {
  auto job = std::make_shared<RenderJob>();
  job->scene = scene_.scene;
  job->settings = settings_;
  job->settings.integrator = renderedCompareIntegrator();
  bool wasPaused = engine_.paused();
  RenderLimits limits = effectiveLimits();
  fitSampleCountToTarget(job->settings, limits.seconds > 0 ? 0 : limits.targetSpp);
  limits.preview = true;
  compareEngine_.start(std::move(job), limits, engineThreads());
  if (wasPaused) compareEngine_.setPaused(true);
  compareSnapshot_ = FilmSnapshot{};
  ++compareRestarts_;
}

void ViewerController::setCompare(bool on) {
  if (on == compare_) return;
  compare_ = on;
  if (!on) {
    compareEngine_.cancel();
    compareSnapshot_ = FilmSnapshot{};
  }
  start();  // both sides start together with their (new) share of the threads
}

bool ViewerController::lightShareOffered() const {
  return !compare_ &&
         offersLightShare(applicableStrategy(settings_.integrator.strategy, sceneHasAreaLights()));
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

void ViewerController::setCompareIntegrator(const IntegratorDesc& d) {
  compareUserChosen_ = true;
  if (d == compareIntegrator_) return;
  compareIntegrator_ = d;
  if (compare_) startCompare();
}

std::vector<Strategy> ViewerController::compareChoices() const {
  std::vector<Strategy> out;
  for (const StrategyRow& row : strategyTable())
    if (!row.samplesProperty.empty() && sameIntegratorType(row.strategy, settings_.integrator.strategy) &&
        strategyApplies(row.strategy, sceneHasAreaLights()))
      out.push_back(row.strategy);
  return out;
}

IntegratorDesc ViewerController::parseCompareStrategy(const std::string& name) const {
  std::vector<Strategy> choices = compareChoices();
  std::string names;
  for (Strategy s : choices) {
    const StrategyRow& row = strategyRow(s);
    if (name == row.shortName || name == row.label) return IntegratorDesc{s, settings_.integrator.samples};
    names += (names.empty() ? "" : ", ") + std::string(row.shortName);
  }
  if (choices.empty())
    throw Error("--compare " + name + ": the scene's " + strategyLabel(settings_.integrator) +
                " has no other strategy to compare with");
  throw Error("--compare " + name + ": expected one strategy that applies to this scene: " + names);
}

// The right side's strategy stays one the scene can render, and differs from the left one when
// another applies.
void ViewerController::chooseCompareDefault() {
  std::vector<Strategy> choices = compareChoices();
  if (choices.empty()) return;
  bool valid = std::find(choices.begin(), choices.end(), compareIntegrator_.strategy) != choices.end();
  if (valid && compareIntegrator_.strategy != settings_.integrator.strategy) return;
  if (valid && compareUserChosen_) return;
  Strategy pick = choices.front();
  for (Strategy s : choices)
    if (s != settings_.integrator.strategy) {
      pick = s;
      break;
    }
  compareIntegrator_.strategy = pick;
}

IntegratorDesc ViewerController::renderedCompareIntegrator() const {
  IntegratorDesc d = compareIntegrator_;
  d.strategy = applicableStrategy(d.strategy, sceneHasAreaLights());
  return d;
}

void ViewerController::setPaused(bool paused) {
  engine_.setPaused(paused);
  if (compare_) compareEngine_.setPaused(paused);
}

namespace {

// Fetches the engine's newest snapshot into `snap`; true when it changed.
bool pollEngine(Engine& engine, FilmSnapshot& snap, bool wantStandardError, bool requestNext) {
  if (requestNext) engine.requestSnapshot(wantStandardError);
  // Paused where no snapshot was requested: publish the pass the film holds.
  if (engine.paused()) engine.publishAtRest();
  bool changed = engine.takeSnapshot(snap);  // the controller is each engine's only reader
  // The engine publishes only at pass boundaries where a snapshot was requested, so the final pass of
  // a finished accumulation may not have been published: read it from the (now idle) film.
  RenderProgress p = engine.progress();
  bool needError = wantStandardError && snap.standardError.empty() && p.spp >= 2;
  if (p.finished && p.spp > 0 && (snap.spp != p.spp || needError || snap.mean.empty())) {
    engine.wait();
    snap.mean = engine.film().mean(p.spp);
    snap.standardError = wantStandardError ? engine.film().standardError(p.spp) : Image();
    snap.spp = p.spp;
    snap.seconds = p.seconds;
    changed = true;
  }
  return changed;
}

}  // namespace

void ViewerController::setProbePixel(int x, int y) {
  probeX_ = x, probeY_ = y;
  engine_.setProbePixel(x, y);
}

bool ViewerController::pollSnapshot(bool wantStandardError, bool requestNext) {
  finishLoading();
  bool changed = pollEngine(engine_, snapshot_, wantStandardError, requestNext);
  // A resting film (paused, finished) publishes no more passes: read the hovered pixel directly.
  if (probeX_ >= 0 && (snapshot_.probe.x != probeX_ || snapshot_.probe.y != probeY_ || changed) &&
      !snapshot_.mean.empty()) {
    FilmSnapshot::Probe probe;
    if (engine_.probeAtRest(probeX_, probeY_, probe) && engine_.progress().spp == snapshot_.spp)
      snapshot_.probe = probe;
  }
  if (changed) snapshotRestart_ = restarts_, snapshotOutput_ = leftOutput_, ++snapshotSerial_;
  if (compare_ && pollEngine(compareEngine_, compareSnapshot_, wantStandardError, requestNext)) {
    changed = true;
    ++compareSnapshotSerial_;
  }
  if (onSnapshotPolled) onSnapshotPolled(*this);
  return changed;
}

bool ViewerController::rendering() const {
  auto busy = [](const Engine& e) { return !e.paused() && !e.progress().finished; };
  return busy(engine_) || (compare_ && busy(compareEngine_));
}

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
  if (s.sampleCount != settings_.sampleCount && limits_.seconds <= 0 &&
      limits_.targetSpp == settings_.sampleCount)
    limits_.targetSpp = s.sampleCount;
  if (s.sampleCount != settings_.sampleCount && chosenTargetSpp_ == settings_.sampleCount)
    chosenTargetSpp_ = s.sampleCount;
  const IntegratorDesc oldCompare = compareIntegrator_;
  settings_ = s;
  chooseCompareDefault();  // the left side's type may have changed
  if (compare_ && !(oldCompare == compareIntegrator_)) {
    start();
    return;
  }
  if (compare_ && onlyIntegrator)
    startLeft();  // the right side renders its own strategy: keep its accumulation
  else
    start();
}

std::vector<Strategy> ViewerController::strategyChoices() const {
  std::vector<Strategy> out;
  for (const StrategyRow& row : strategyTable())
    if (allLightsRow(row.strategy) == row.strategy) out.push_back(row.strategy);
  return out;
}

void ViewerController::setStrategy(Strategy choice) {
  RenderSettings s = settings_;
  const Strategy live = s.integrator.strategy;
  const LightSelection keep =
      penumbra::takesLightSelection(live) ? lightSelectionOf(live) : defaultLightSelection();
  s.integrator.strategy = withLightSelection(choice, keep).value_or(choice);
  setSettings(s);
}

std::string ViewerController::strategyUnavailableReason(Strategy choice) const {
  const StrategyRow& row = strategyRow(choice);
  if (!strategyApplies(choice, sceneHasAreaLights()))
    return std::string(sceneNeedText(row.needs)) + " (renders " +
           std::string(strategyRow(applicableStrategy(choice, false)).label) + " here)";
  const bool deltaLights = scene_.scene && scene_.scene->hasDeltaLights();
  // simple lights with point and directional lights only; the hemisphere strategies find area
  // lights by chance and add the point and directional ones: without any, both render black.
  if (choice == Strategy::Simple && !deltaLights) return "needs point or directional lights";
  const bool hemisphere =
      choice == Strategy::DirectUniformHemisphere || choice == Strategy::DirectCosineHemisphere;
  if (hemisphere && !deltaLights && !sceneHasAreaLights()) return "needs lights: the scene has none";
  return {};
}

bool ViewerController::takesLightSelection() const {
  return penumbra::takesLightSelection(settings_.integrator.strategy);
}

void ViewerController::setLightSelection(LightSelection selection) {
  std::optional<Strategy> row = withLightSelection(settings_.integrator.strategy, selection);
  if (!row) return;
  RenderSettings s = settings_;
  s.integrator.strategy = *row;
  setSettings(s);
}

size_t ViewerController::sphereLightCount() const {
  return scene_.scene ? scene_.scene->sphereLights.size() : 0;
}

LightSelection ViewerController::defaultLightSelection() const {
  return penumbra::defaultLightSelection(sphereLightCount());
}

std::string ViewerController::lightSelectionDefaultText() const {
  return "default for " + sphereLightsText(sphereLightCount()) + ": " +
         std::string(lightSelectionName(defaultLightSelection())) + " (" +
         std::string(lightSelectionName(LightSelection::All)) + " up to " + std::to_string(kAllLightsUpTo) +
         ")";
}

void ViewerController::setStopRule(StopRule rule) {
  if (rule == StopRule::TimeBudget)
    setTimeBudget(chosenSeconds_);
  else
    setTargetSpp(chosenTargetSpp_);
}

void ViewerController::setTargetSpp(uint32_t spp) {
  RenderLimits l = limits_;
  l.targetSpp = spp;
  l.seconds = 0;
  setLimits(l);
}

void ViewerController::setTimeBudget(double seconds) {
  RenderLimits l = limits_;
  l.targetSpp = 0;
  l.seconds = seconds > 0 ? seconds : kDefaultSeconds;
  setLimits(l);
}

void ViewerController::setLimits(const RenderLimits& l) {
  // Each rule remembers its value for when the user switches back to it.
  if (l.seconds > 0)
    chosenSeconds_ = l.seconds;
  else
    chosenTargetSpp_ = l.targetSpp;
  if (l.targetSpp == limits_.targetSpp && l.seconds == limits_.seconds) return;
  limits_ = l;
  // A sampler shaped by the count (stratified, zsobol) needs a new pattern for a new target.
  if (samplerRow(settings_.samplerKind).usesSampleCount) return start();
  const RenderLimits run = effectiveLimits();
  if (!engine_.extend(run)) startLeft();  // a new target continues the accumulation
  if (compare_ && !compareEngine_.extend(run)) startCompare();
}

// ---- camera ---------------------------------------------------------------------------------------

void ViewerController::applyOrbit(const Vec3& origin) {
  orbit_.isLookAt = true;  // an orbit makes the camera the lookat about the target
  moveCamera(origin, orbit_.target);
}

// Sets the camera to `origin`, looking about `target` as before: a lookat camera is rebuilt from the
// two, any other keeps its rotation.
void ViewerController::moveCamera(const Vec3& origin, const Vec3& target) {
  RenderSettings s = settings_;
  if (orbit_.isLookAt) {
    const glm::mat4 toWorld = lookAt(origin, target, orbit_.worldUp);
    // Far from the world's origin a camera dollied close to its target rounds onto it (floats are
    // ~0.1 apart at 1e6): with no direction to look along, the camera stays where it is.
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(toWorld[c][r])) return;
    s.camera.toWorld = toWorld;
  } else {
    s.camera.toWorld[3] = glm::vec4(origin, 1.f);
  }
  orbit_.moved = true;
  orbit_.target = target;
  setSettings(s);
}

float ViewerController::clearDistance(const Vec3& from, const Vec3& direction, float wanted) const {
  if (!scene_.scene || !(wanted > 0.f)) return wanted;
  const float nearGap = 2.f * settings_.camera.nearClip;
  Ray ray{from, direction, 0.f, wanted * 1.05f + nearGap};
  SurfaceHit hit;
  if (!scene_.scene->geometry.intersect(ray, hit)) return wanted;
  // Stop short of the surface by 2 % of the way to it (at least twice the near clip distance).
  const float gap = std::max(nearGap, 0.02f * hit.t);
  return std::clamp(hit.t - gap, 0.f, wanted);
}

namespace {
float heightAbove(const OrbitCamera& o, const Vec3& p) {
  return glm::dot(p - o.horizonPoint, o.worldUp);
}
constexpr const char* kBelowHorizon = kCameraLimitNotes[0];
constexpr const char* kAtSurface = kCameraLimitNotes[1];
}  // namespace

void ViewerController::orbit(float dx, float dy) {
  const glm::mat4& m = settings_.camera.toWorld;
  Vec3 origin(m[3]);
  Vec3 offset = origin - orbit_.target;
  const float k = 0.005f;  // radians per pixel
  glm::mat4 yaw = glm::rotate(glm::mat4(1.f), dx * k, orbit_.worldUp);
  offset = Vec3(yaw * glm::vec4(offset, 0.f));
  Vec3 left = glm::normalize(glm::cross(orbit_.worldUp, -offset));
  Vec3 pitched = Vec3(glm::rotate(glm::mat4(1.f), -dy * k, left) * glm::vec4(offset, 0.f));
  // Stop short of the poles, where the up vector would flip, and of the lower hemisphere (below the
  // ground the image goes black): the pitch stops at the limit rather than past it. A target panned
  // below the horizon plane cannot take the camera under it either.
  const float elevation = glm::dot(glm::normalize(pitched), orbit_.worldUp);
  const bool aboveFloor = heightAbove(orbit_, orbit_.target + pitched) >= orbit_.minHeight - 1e-6f ||
                          heightAbove(orbit_, orbit_.target + pitched) >= heightAbove(orbit_, origin);
  if (std::abs(elevation) < 0.995f && elevation >= orbit_.minElevationSin - 1e-6f && aboveFloor) {
    offset = pitched;
    cameraLimitNote_.clear();
  } else if (dy != 0.f && (elevation < orbit_.minElevationSin - 1e-6f || !aboveFloor)) {
    cameraLimitNote_ = kBelowHorizon;
  }
  applyOrbit(orbit_.target + offset);
}

void ViewerController::pan(float dx, float dy) {
  const glm::mat4& m = settings_.camera.toWorld;
  Vec3 left(m[0]), up(m[1]), origin(m[3]);
  // One pixel moves the target by the size of a pixel at the target's distance.
  float pixel = 2.f * orbit_.distance * std::tan(glm::radians(settings_.camera.fovDegrees) * 0.5f) /
                float(std::max(settings_.camera.width, 1));
  Vec3 shift = (left * dx + up * dy) * pixel;
  cameraLimitNote_.clear();
  // Never below the horizon plane: the part of the shift that would go there is dropped.
  const float below = orbit_.minHeight - heightAbove(orbit_, origin + shift);
  if (below > 0.f && glm::dot(shift, orbit_.worldUp) < 0.f) {
    shift += std::min(below, -glm::dot(shift, orbit_.worldUp)) * orbit_.worldUp;
    cameraLimitNote_ = kBelowHorizon;
  }
  const float length = glm::length(shift);
  if (!(length > 0.f)) return;
  const float clear = clearDistance(origin, shift / length, length);
  if (clear < length) {
    shift *= clear / length;
    cameraLimitNote_ = kAtSurface;
  }
  moveCamera(origin + shift, orbit_.target + shift);
}

void ViewerController::dolly(float steps) {
  const glm::mat4& m = settings_.camera.toWorld;
  const Vec3 forward = glm::normalize(Vec3(m[2])), origin(m[3]);
  const float wanted = std::clamp(orbit_.distance * std::pow(0.9f, steps), 1e-3f, 1e5f);
  float distance = wanted;
  cameraLimitNote_.clear();
  // Moving back while looking up lowers the camera: not under the horizon plane.
  const float rise = -glm::dot(forward, orbit_.worldUp);  // height gained per unit of distance
  if (rise < 0.f && distance > orbit_.distance) {
    const float lowest = heightAbove(orbit_, orbit_.target);
    const float maxDistance = (orbit_.minHeight - lowest) / rise;
    if (distance > maxDistance) {
      distance = std::max(orbit_.distance, maxDistance);
      cameraLimitNote_ = kBelowHorizon;
    }
  }
  // Not through a surface, forwards or backwards.
  const float move = orbit_.distance - distance;
  const float clear = clearDistance(origin, move > 0.f ? forward : -forward, std::abs(move));
  if (clear < std::abs(move)) {
    distance = orbit_.distance - std::copysign(clear, move);
    cameraLimitNote_ = kAtSurface;
  }
  orbit_.distance = distance;
  moveCamera(orbit_.target - forward * distance, orbit_.target);
}

void ViewerController::setFov(float degrees) {
  RenderSettings s = settings_;
  s.camera.fovDegrees = std::clamp(degrees, 1.f, 179.f);
  setSettings(s);
}

void ViewerController::resetCamera() {
  settings_.camera = scene_.settings.camera;  // initOrbitFromCamera clears the limit note
  initOrbitFromCamera();
  start();
}

// ---- scene ----------------------------------------------------------------------------------------

fs::file_time_type ViewerController::mtimeOf(const std::string& path) const {
  std::error_code ec;
  auto t = fs::last_write_time(path, ec);
  return ec ? fs::file_time_type{} : t;
}

void ViewerController::rememberRecent(const std::string& path) {
  std::string abs = fs::absolute(path).lexically_normal().string();
  recent_.erase(std::remove(recent_.begin(), recent_.end(), abs), recent_.end());
  recent_.insert(recent_.begin(), abs);
  if (recent_.size() > 10) recent_.resize(10);
}

void ViewerController::adoptLoaded(LoadedScene loaded, const std::string& path, double seconds) {
  adoptScene(std::move(loaded));
  rememberRecent(path);
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

static double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool ViewerController::openScene(const std::string& path) {
  auto t0 = std::chrono::steady_clock::now();
  try {
    LoadedScene loaded = loadScene(path, overrides_);
    blockingLoadSeconds_ += secondsSince(t0);
    adoptLoaded(std::move(loaded), path, secondsSince(t0));
    return true;
  } catch (const std::exception& e) {
    blockingLoadSeconds_ += secondsSince(t0);
    sceneError_ = e.what();
    return false;
  }
}

void ViewerController::openSceneAsync(const std::string& path) {
  if (loading_.valid()) {  // one load at a time; the newest request wins below
    auto t0 = std::chrono::steady_clock::now();
    loading_.wait();
    blockingLoadSeconds_ += secondsSince(t0);
  }
  loadingPath_ = path;
  loadStart_ = std::chrono::steady_clock::now();
  sceneStatus_ = "loading " + path + " ...";
  loading_ =
      std::async(std::launch::async, [path, overrides = overrides_] { return loadScene(path, overrides); });
}

bool ViewerController::finishLoading() {
  if (!loading_.valid() || loading_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return false;
  const double seconds = secondsSince(loadStart_);
  try {
    adoptLoaded(loading_.get(), loadingPath_, seconds);
  } catch (const std::exception& e) {
    sceneError_ = e.what();
    sceneStatus_.clear();
  }
  loading_ = {};
  return true;
}

double ViewerController::secondsSinceRestart() const {
  return secondsSince(restartTime_);
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
  const RenderSettings oldFile = scene_.settings, live = settings_;
  const RenderLimits oldLimits = limits_;
  const uint32_t oldTargetSpp = chosenTargetSpp_;
  const double oldSeconds = chosenSeconds_;
  const OrbitCamera oldOrbit = orbit_;
  LoadedScene loaded;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    loaded = loadScene(path, overrides_);
    blockingLoadSeconds_ += secondsSince(t0);
  } catch (const std::exception& e) {
    blockingLoadSeconds_ += secondsSince(t0);
    sceneError_ = e.what();
    sceneMtime_ = mtimeOf(path);  // do not retry until the file changes again
    return false;
  }
  // A setting the user changed in the UI survives unless the file changed that same setting.
  const RenderSettings& newFile = loaded.settings;
  std::vector<std::string> kept;
  RenderSettings s = newFile;
  auto keep = [&](bool userChanged, bool fileSame, const char* name, auto apply) {
    if (userChanged && fileSame) {
      apply();
      kept.push_back(name);
    }
  };
  keep(!(live.camera == oldFile.camera), newFile.camera == oldFile.camera, "camera",
       [&] { s.camera = live.camera; });
  keep(!(live.integrator == oldFile.integrator), newFile.integrator == oldFile.integrator, "integrator",
       [&] { s.integrator = live.integrator; });
  keep(live.samplerKind != oldFile.samplerKind || live.sampleCount != oldFile.sampleCount ||
           live.seed != oldFile.seed,
       newFile.samplerKind == oldFile.samplerKind && newFile.sampleCount == oldFile.sampleCount &&
           newFile.seed == oldFile.seed,
       "sampler",
       [&] { s.samplerKind = live.samplerKind, s.sampleCount = live.sampleCount, s.seed = live.seed; });
  const bool limitsChanged = oldLimits.seconds > 0 || oldLimits.targetSpp != oldFile.sampleCount;
  adoptScene(std::move(loaded));
  settings_ = s;
  if (limitsChanged) {
    limits_ = oldLimits;
    chosenTargetSpp_ = oldTargetSpp, chosenSeconds_ = oldSeconds;
    kept.push_back("limits");
  } else {
    limits_.targetSpp = settings_.sampleCount;
  }
  if (std::find(kept.begin(), kept.end(), "camera") != kept.end()) orbit_ = oldOrbit;
  chooseCompareDefault();
  sceneStatus_ = "reloaded " + fs::path(path).filename().string();
  if (!kept.empty()) {
    sceneStatus_ += "; kept your ";
    for (size_t i = 0; i < kept.size(); ++i) sceneStatus_ += (i ? ", " : "") + kept[i];
  }
  start();
  return true;
}

bool ViewerController::checkFileChanged() {
  if (scene_.path.empty()) return false;
  auto now = std::chrono::steady_clock::now();
  if (now - lastMtimeCheck_ < std::chrono::milliseconds(500)) return false;
  lastMtimeCheck_ = now;
  auto t = mtimeOf(scene_.path);
  if (t == sceneMtime_ || t == fs::file_time_type{}) return false;
  reloadScene();
  return true;
}

std::vector<std::string> ViewerController::siblingScenes() const {
  std::vector<std::string> out;
  fs::path dir = scene_.path.empty() ? fs::current_path() : fs::path(scene_.path).parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && e.path().extension() == ".xml") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

// ---- output ---------------------------------------------------------------------------------------

SceneNode ViewerController::liveDesc(const std::string& saveDir) const {
  SceneWriteOptions options;
  options.outputDir = saveDir;
  // A lookat camera is written as its <lookat>: a reload orbits about the same target and up.
  if (orbit_.isLookAt)
    options.cameraLookAt = CameraLookAt{Vec3(settings_.camera.toWorld[3]), orbit_.target, orbit_.worldUp};
  return sceneWithSettings(scene_.desc, settings_, options);
}

std::string ViewerController::liveSceneXml(const std::string& saveDir) const {
  return writeSceneXml(liveDesc(saveDir));
}

std::string ViewerController::saveImage(const std::string& path) const {
  if (snapshot_.mean.empty()) throw Error(path + ": nothing rendered yet");
  ImageMetadata meta;
  for (auto& [k, v] : describeSettings(settings_)) meta.add(k, v);
  meta.add("spp", std::to_string(snapshot_.spp));
  meta.add("seconds", std::to_string(snapshot_.seconds));
  meta.add("scene", scene_.path.empty() ? "<built-in>" : scene_.path);
  if (snapshotIsLightShare()) {
    // EXR/PFM: the split (R light, G cosine, B the rest, as luminance); PNG: the false-colour map.
    meta.add("output", "mis-light-share");
    if (imageFormatFromPath(path) == ImageFormat::Png) {
      writeImage(path, lightShareMapImage(snapshot_.mean), meta, 0.f);
      return "saved " + path + " (MIS light share, " + std::to_string(snapshot_.spp) + " spp)";
    }
  }
  writeImage(path, snapshot_.mean, meta, display.exposure);
  return "saved " + path + " (" + std::to_string(snapshot_.spp) + " spp)";
}

std::string ViewerController::saveSceneAs(const std::string& path) const {
  fs::path dir = fs::path(path).parent_path();
  std::string xml = liveSceneXml(dir.empty() ? "." : dir.string());
  writeBytesAtomically(path, xml.data(), xml.size());
  return "saved " + path;
}

}  // namespace penumbra::ui
