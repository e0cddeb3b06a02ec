#include "app/ui/overwrite_guard.h"

#include <filesystem>
#include <system_error>

namespace penumbra::ui {

bool OverwriteGuard::allows(const std::string& path) {
  std::error_code ec;
  const bool exists = std::filesystem::exists(std::filesystem::path(path), ec);
  if (!exists || armed_ == path) {
    armed_.clear();
    return true;
  }
  armed_ = path;
  return false;
}

std::string OverwriteGuard::refusal(const std::string& path, const char* button) {
  return path + " exists: press " + button + " again to replace it";
}

}  // namespace penumbra::ui
