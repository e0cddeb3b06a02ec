// Saving from the viewer over a file that already exists takes a second request for the same path:
// the first one only says what would be replaced. A path that names no file is written at once.
// Plain state without ImGui, so the rule is tested without a window.
#pragma once

#include <string>

namespace penumbra::ui {

class OverwriteGuard {
 public:
  // True when `path` may be written now: it names no file, or the request just before was for the
  // same path. Otherwise false, and the next request for `path` is allowed.
  bool allows(const std::string& path);
  // What the viewer says when allows(path) was false.
  static std::string refusal(const std::string& path, const char* button);

 private:
  std::string armed_;  // the path the last refused request named
};

}  // namespace penumbra::ui
