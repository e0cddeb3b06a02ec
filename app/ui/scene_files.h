// The viewer's scene files: loading (on the calling thread, or on a loader thread so that a large
// mesh's BVH build does not stop the UI), watching the open file for changes, and the recent and
// sibling scenes the Scene panel offers. What a reload keeps of the user's changes is reload_rules.h.
#pragma once

#include <chrono>
#include <filesystem>
#include <future>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/scene_builder.h"

namespace penumbra::ui {

class SceneFiles {
 public:
  using Overrides = std::vector<std::pair<std::string, std::string>>;

  // Every load applies `overrides` (the command line's --set).
  explicit SceneFiles(Overrides overrides) : overrides_(std::move(overrides)) {}
  ~SceneFiles();  // waits for a load in flight (the loader thread reads nothing but its arguments)
  SceneFiles(const SceneFiles&) = delete;
  SceneFiles& operator=(const SceneFiles&) = delete;

  // Loads on the calling thread and sets `seconds` to the load's wall time; throws penumbra::Error.
  LoadedScene load(const std::string& path, double& seconds);
  // Loads on a thread; one load at a time: a load in flight is waited for first, and the newest
  // request is the one that finishes.
  void loadAsync(const std::string& path);
  bool loading() const { return loading_.valid(); }
  const std::string& loadingPath() const { return loadingPath_; }
  // Whether the asynchronous load has finished (takeLoaded then returns at once).
  bool loadFinished() const;
  // Seconds since the asynchronous load started.
  double loadingSeconds() const;
  // The finished load's scene; rethrows its error. Either way the load is over.
  LoadedScene takeLoaded();
  // Seconds the calling thread has spent loading in all: load(), and loadAsync waiting for the
  // previous load.
  double blockingSeconds() const { return blockingSeconds_; }

  // The file changed() watches ("" watches nothing), from its modification time now.
  void watch(const std::string& path);
  // Whether the watched file's modification time changed since watch(); looks at most twice a second.
  bool changed();

  // The most recent first, at most 10, each once (absolute, normalised).
  void rememberRecent(const std::string& path);
  const std::vector<std::string>& recent() const { return recent_; }

 private:
  Overrides overrides_;
  std::future<LoadedScene> loading_;
  std::string loadingPath_;
  std::chrono::steady_clock::time_point loadStart_{};
  double blockingSeconds_ = 0;
  std::string watched_;
  std::filesystem::file_time_type watchedMtime_{};
  std::chrono::steady_clock::time_point lastCheck_{};
  std::vector<std::string> recent_;
};

// The .xml files in the directory of `scenePath` (the current directory for ""), sorted.
std::vector<std::string> siblingScenes(const std::string& scenePath);

}  // namespace penumbra::ui
