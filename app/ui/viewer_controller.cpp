#include "app/ui/viewer_controller.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

#include "core/image/atomic_file.h"
#include "core/image/image_io.h"
#include "core/math/error.h"
#include "core/math/frame.h"
#include "core/render/sample_count_fit.h"
#include "core/sampling/sampler_table.h"
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
  compareEngine_.cancel();
  engine_.cancel();
}

void ViewerController::adoptScene(LoadedScene loaded) {
  scene_ = std::move(loaded);
  settings_ = scene_.settings;
  limits_ = RenderLimits{};
  limits_.targetSpp = settings_.sampleCount;
  sceneError_.clear();
  sceneMtime_ = scene_.path.empty() ? fs::file_time_type{} : mtimeOf(scene_.path);
  initOrbitFromCamera();
}

void ViewerController::initOrbitFromCamera() {
  const glm::mat4& m = settings_.camera.toWorld;
  Vec3 origin(m[3]), forward = glm::normalize(Vec3(m[2]));
  orbit_.worldUp = glm::normalize(Vec3(m[1]));
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

void ViewerController::startLeft() {
  auto job = std::make_shared<RenderJob>();
  job->scene = scene_.scene;
  job->settings = settings_;
  samplerNote_ = fitSampleCountToTarget(job->settings, useTimeBudget_ ? 0 : limits_.targetSpp);
  bool wasPaused = engine_.paused();
  RenderLimits limits = limits_;
  limits.preview = true;  // a coarse first frame within milliseconds of any change
  engine_.start(std::move(job), limits, engineThreads());
  if (wasPaused) engine_.setPaused(true);
  ++restarts_;
}

void ViewerController::startCompare() {
  auto job = std::make_shared<RenderJob>();
  job->scene = scene_.scene;
  job->settings = settings_;
  fitSampleCountToTarget(job->settings, useTimeBudget_ ? 0 : limits_.targetSpp);
  job->settings.integrator = renderedCompareIntegrator();
  bool wasPaused = engine_.paused();
  RenderLimits limits = limits_;
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

void ViewerController::setCompareIntegrator(const IntegratorDesc& d) {
  if (d == compareIntegrator_) return;
  compareIntegrator_ = d;
  if (compare_) startCompare();
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
  bool changed = pollEngine(engine_, snapshot_, wantStandardError, requestNext);
  // A resting film (paused, finished) publishes no more passes: read the hovered pixel directly.
  if (probeX_ >= 0 && (snapshot_.probe.x != probeX_ || snapshot_.probe.y != probeY_ || changed) &&
      !snapshot_.mean.empty()) {
    FilmSnapshot::Probe probe;
    if (engine_.probeAtRest(probeX_, probeY_, probe) && engine_.progress().spp == snapshot_.spp)
      snapshot_.probe = probe;
  }
  if (changed) snapshotRestart_ = restarts_, ++snapshotSerial_;
  if (compare_ && pollEngine(compareEngine_, compareSnapshot_, wantStandardError, requestNext)) {
    changed = true;
    ++compareSnapshotSerial_;
  }
  return changed;
}

bool ViewerController::rendering() const {
  auto busy = [](const Engine& e) { return !e.paused() && !e.progress().finished; };
  return busy(engine_) || (compare_ && busy(compareEngine_));
}

static bool sameSettings(const RenderSettings& a, const RenderSettings& b) {
  return a.camera.toWorld == b.camera.toWorld && a.camera.fovDegrees == b.camera.fovDegrees &&
         a.camera.width == b.camera.width && a.camera.height == b.camera.height &&
         a.camera.nearClip == b.camera.nearClip && a.camera.farClip == b.camera.farClip &&
         std::memcmp(&a.filter, &b.filter, sizeof a.filter) == 0 && a.samplerKind == b.samplerKind &&
         a.sampleCount == b.sampleCount && a.seed == b.seed && a.integrator == b.integrator;
}

void ViewerController::setSettings(const RenderSettings& s) {
  if (sameSettings(s, settings_)) return;
  RenderSettings sameIntegrator = s;
  sameIntegrator.integrator = settings_.integrator;
  bool onlyIntegrator = sameSettings(sameIntegrator, settings_);
  settings_ = s;
  if (compare_ && onlyIntegrator)
    startLeft();  // the right side renders its own strategy: keep its accumulation
  else
    start();
}

void ViewerController::setLimits(const RenderLimits& l) {
  if (l.targetSpp == limits_.targetSpp && l.seconds == limits_.seconds) return;
  limits_ = l;
  useTimeBudget_ = l.seconds > 0;
  // A sampler shaped by the count (stratified, zsobol) needs a new pattern for a new target.
  if (samplerRow(settings_.samplerKind).usesSampleCount) return start();
  if (!engine_.extend(limits_)) startLeft();  // a new target continues the accumulation
  if (compare_ && !compareEngine_.extend(limits_)) startCompare();
}

// ---- camera ---------------------------------------------------------------------------------------

void ViewerController::applyOrbit(const Vec3& origin) {
  RenderSettings s = settings_;
  s.camera.toWorld = lookAt(origin, orbit_.target, orbit_.worldUp);
  setSettings(s);
}

void ViewerController::orbit(float dx, float dy) {
  const glm::mat4& m = settings_.camera.toWorld;
  Vec3 origin(m[3]);
  Vec3 offset = origin - orbit_.target;
  const float k = 0.005f;  // radians per pixel
  glm::mat4 yaw = glm::rotate(glm::mat4(1.f), dx * k, orbit_.worldUp);
  offset = Vec3(yaw * glm::vec4(offset, 0.f));
  Vec3 left = glm::normalize(glm::cross(orbit_.worldUp, -offset));
  Vec3 pitched = Vec3(glm::rotate(glm::mat4(1.f), -dy * k, left) * glm::vec4(offset, 0.f));
  // Stop short of the poles, where the up vector would flip.
  if (std::abs(glm::dot(glm::normalize(pitched), orbit_.worldUp)) < 0.995f) offset = pitched;
  applyOrbit(orbit_.target + offset);
}

void ViewerController::pan(float dx, float dy) {
  const glm::mat4& m = settings_.camera.toWorld;
  Vec3 left(m[0]), up(m[1]), origin(m[3]);
  // One pixel moves the target by the size of a pixel at the target's distance.
  float pixel = 2.f * orbit_.distance * std::tan(glm::radians(settings_.camera.fovDegrees) * 0.5f) /
                float(std::max(settings_.camera.width, 1));
  Vec3 shift = (left * dx + up * dy) * pixel;
  orbit_.target += shift;
  RenderSettings s = settings_;
  s.camera.toWorld[3] = glm::vec4(origin + shift, 1.f);
  setSettings(s);
}

void ViewerController::dolly(float steps) {
  const glm::mat4& m = settings_.camera.toWorld;
  Vec3 forward(m[2]);
  orbit_.distance = std::clamp(orbit_.distance * std::pow(0.9f, steps), 1e-3f, 1e5f);
  RenderSettings s = settings_;
  s.camera.toWorld[3] = glm::vec4(orbit_.target - glm::normalize(forward) * orbit_.distance, 1.f);
  setSettings(s);
}

void ViewerController::setFov(float degrees) {
  RenderSettings s = settings_;
  s.camera.fovDegrees = std::clamp(degrees, 1.f, 179.f);
  setSettings(s);
}

void ViewerController::resetCamera() {
  settings_.camera = scene_.settings.camera;
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

bool ViewerController::openScene(const std::string& path) {
  try {
    LoadedScene loaded = loadScene(path, overrides_);
    adoptScene(std::move(loaded));
    rememberRecent(path);
    start();
    return true;
  } catch (const std::exception& e) {
    sceneError_ = e.what();
    return false;
  }
}

bool ViewerController::reloadScene() {
  if (scene_.path.empty()) {
    sceneError_.clear();
    start();
    return true;
  }
  std::string path = scene_.path;
  bool ok = openScene(path);
  if (!ok) sceneMtime_ = mtimeOf(path);  // do not retry until the file changes again
  return ok;
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

namespace {

Property makeProp(const std::string& name, PropertyType type, const std::string& text) {
  Property p;
  if (!parsePropertyValue(type, text, p)) throw Error("internal: cannot encode " + name + " = " + text);
  p.name = name;
  p.used = true;
  return p;
}

// Replaces (or adds) the named properties, dropping any alias spellings listed in `drop`.
void replaceProps(SceneNode& node, const std::vector<Property>& props, std::vector<std::string> drop) {
  for (const Property& p : props) drop.push_back(p.name);
  PropertyList out;
  out.setContext(node.file, node.tag, node.type);
  for (const Property& p : node.props.properties())
    if (std::find(drop.begin(), drop.end(), p.name) == drop.end()) out.add(p);
  for (const Property& p : props) out.add(p);
  node.props = std::move(out);
}

SceneNode& childOrNew(SceneNode& root, const std::string& tag, const std::string& type) {
  for (SceneNode& c : root.children)
    if (c.tag == tag) return c;
  SceneNode n;
  n.tag = tag;
  n.type = type;
  n.file = root.file;
  n.baseDir = root.baseDir;
  root.children.push_back(std::move(n));
  return root.children.back();
}

std::string matrixText(const glm::mat4& m) {  // row-major, 16 numbers
  std::string s;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) s += (s.empty() ? "" : " ") + formatFloat(m[c][r]);
  return s;
}

}  // namespace

SceneNode ViewerController::liveDesc() const {
  SceneNode root = scene_.desc;
  const RenderSettings& s = settings_;

  SceneNode& cam = childOrNew(root, "camera", "perspective");
  replaceProps(cam,
               {makeProp("toWorld", PropertyType::Transform, matrixText(s.camera.toWorld)),
                makeProp("fov", PropertyType::Float, formatFloat(s.camera.fovDegrees)),
                makeProp("width", PropertyType::Integer, std::to_string(s.camera.width)),
                makeProp("height", PropertyType::Integer, std::to_string(s.camera.height))},
               {});

  SceneNode& smp = childOrNew(root, "sampler", samplerKindName(s.samplerKind));
  smp.type = samplerKindName(s.samplerKind);
  replaceProps(smp,
               {makeProp("sampleCount", PropertyType::Integer, std::to_string(s.sampleCount)),
                makeProp("seed", PropertyType::Integer, std::to_string(s.seed))},
               {});

  const std::string type(strategyRow(s.integrator.strategy).xmlType);
  SceneNode& integ = childOrNew(root, "integrator", type);
  integ.type = type;
  integ.props = PropertyList();
  integ.props.setContext(integ.file, integ.tag, integ.type);
  for (const CanonicalProperty& p : canonicalProperties(s.integrator))
    integ.props.add(
        makeProp(std::string(p.name), p.isInteger ? PropertyType::Integer : PropertyType::String, p.value));
  return root;
}

std::string ViewerController::liveSceneXml() const {
  return writeSceneXml(liveDesc());
}

std::string ViewerController::saveImage(const std::string& path) const {
  if (snapshot_.mean.empty()) throw Error(path + ": nothing rendered yet");
  ImageMetadata meta;
  for (auto& [k, v] : describeSettings(settings_)) meta.add(k, v);
  meta.add("spp", std::to_string(snapshot_.spp));
  meta.add("seconds", std::to_string(snapshot_.seconds));
  meta.add("scene", scene_.path.empty() ? "<built-in>" : scene_.path);
  writeImage(path, snapshot_.mean, meta, display.exposure);
  return "saved " + path + " (" + std::to_string(snapshot_.spp) + " spp)";
}

std::string ViewerController::saveSceneAs(const std::string& path) const {
  std::string xml = liveSceneXml();
  writeBytesAtomically(path, xml.data(), xml.size());
  return "saved " + path;
}

}  // namespace penumbra::ui
