// Shared helpers for end-to-end tests: paths of the repository's files and the assignment's scenes.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace penumbra::test {

inline std::string sourcePath(const std::string& relative) {
  return std::string(PENUMBRA_SOURCE_DIR) + "/" + relative;
}

// The assignment's scene files shipped under scenes/ (hw0, hw1, hw2, dev-scenes), sorted.
inline std::vector<std::string> assignmentSceneFiles() {
  std::vector<std::string> out;
  for (const char* dir : {"hw0", "hw1", "hw2", "dev-scenes"})
    for (const auto& e : std::filesystem::recursive_directory_iterator(sourcePath("scenes/") + dir))
      if (e.is_regular_file() && e.path().extension() == ".xml") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace penumbra::test
