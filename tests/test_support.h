// Shared helpers for end-to-end tests: scenes from XML strings, per-point Monte Carlo estimates with
// their standard error, and paths of the repository and the built executable.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/analysis/ray_estimate.h"
#include "core/sampling/sampler.h"
#include "core/scene/scene_builder.h"
#include "core/world/scene.h"

namespace penumbra::test {

inline std::string sourcePath(const std::string& relative) {
  return std::string(PENUMBRA_SOURCE_DIR) + "/" + relative;
}

// The seed assignment's scene files shipped under scenes/ (hw0, hw1, hw2, dev-scenes), sorted.
inline std::vector<std::string> seedSceneFiles() {
  std::vector<std::string> out;
  for (const char* dir : {"hw0", "hw1", "hw2", "dev-scenes"})
    for (const auto& e : std::filesystem::recursive_directory_iterator(sourcePath("scenes/") + dir))
      if (e.is_regular_file() && e.path().extension() == ".xml") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

// The estimator helpers live in core/analysis/ray_estimate.h (shared with `penumbra check`).
using analysis::Estimate;
using analysis::estimateRay;
using analysis::rayOnto;

}  // namespace penumbra::test
