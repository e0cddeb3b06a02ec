#include "app/ui/scene_files.h"

#include <algorithm>

namespace penumbra::ui {

namespace fs = std::filesystem;

namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

fs::file_time_type mtimeOf(const std::string& path) {
  std::error_code ec;
  auto t = fs::last_write_time(path, ec);
  return ec ? fs::file_time_type{} : t;
}

}  // namespace

SceneFiles::~SceneFiles() {
  if (loading_.valid()) loading_.wait();
}

LoadedScene SceneFiles::load(const std::string& path, double& seconds) {
  const auto t0 = std::chrono::steady_clock::now();
  try {
    LoadedScene loaded = loadScene(path, overrides_);
    seconds = secondsSince(t0);
    blockingSeconds_ += seconds;
    return loaded;
  } catch (...) {
    blockingSeconds_ += secondsSince(t0);
    throw;
  }
}

void SceneFiles::loadAsync(const std::string& path) {
  if (loading_.valid()) {  // one load at a time; the newest request wins below
    auto t0 = std::chrono::steady_clock::now();
    loading_.wait();
    blockingSeconds_ += secondsSince(t0);
  }
  loadingPath_ = path;
  loadStart_ = std::chrono::steady_clock::now();
  loading_ =
      std::async(std::launch::async, [path, overrides = overrides_] { return loadScene(path, overrides); });
}

bool SceneFiles::loadFinished() const {
  return loading_.valid() && loading_.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

double SceneFiles::loadingSeconds() const {
  return secondsSince(loadStart_);
}

LoadedScene SceneFiles::takeLoaded() {
  std::future<LoadedScene> done = std::move(loading_);
  return done.get();
}

void SceneFiles::watch(const std::string& path) {
  watched_ = path;
  watchedMtime_ = path.empty() ? fs::file_time_type{} : mtimeOf(path);
}

bool SceneFiles::changed() {
  if (watched_.empty()) return false;
  auto now = std::chrono::steady_clock::now();
  if (now - lastCheck_ < std::chrono::milliseconds(500)) return false;
  lastCheck_ = now;
  auto t = mtimeOf(watched_);
  return t != watchedMtime_ && t != fs::file_time_type{};
}

void SceneFiles::rememberRecent(const std::string& path) {
  std::string abs = fs::absolute(path).lexically_normal().string();
  recent_.erase(std::remove(recent_.begin(), recent_.end(), abs), recent_.end());
  recent_.insert(recent_.begin(), abs);
  if (recent_.size() > 10) recent_.resize(10);
}

std::vector<std::string> siblingScenes(const std::string& scenePath) {
  std::vector<std::string> out;
  fs::path dir = scenePath.empty() ? fs::current_path() : fs::path(scenePath).parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && e.path().extension() == ".xml") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace penumbra::ui
