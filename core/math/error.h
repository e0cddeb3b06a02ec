// Errors that carry where they came from (file and line), so users see "scene.xml:12: expected ...".
#pragma once

#include <stdexcept>
#include <string>

namespace penumbra {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
  Error(const std::string& file, int line, const std::string& message)
      : std::runtime_error(locate(file, line) + message), file_(file), line_(line) {}

  const std::string& file() const { return file_; }
  int line() const { return line_; }

 private:
  static std::string locate(const std::string& file, int line) {
    if (file.empty()) return {};
    return line > 0 ? file + ":" + std::to_string(line) + ": " : file + ": ";
  }
  std::string file_;
  int line_ = 0;
};

}  // namespace penumbra
