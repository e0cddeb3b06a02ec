// The readers under test take a path: each input is written to one scratch file per fuzzer process
// (in $TMPDIR), which is removed when the process exits.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace penumbra::fuzz {

class ScratchFile {
 public:
  explicit ScratchFile(const std::string& extension) {
    std::filesystem::path dir = std::filesystem::temp_directory_path();
    path_ = (dir / ("penumbra-fuzz-" + std::to_string(::getpid()) + extension)).string();
  }
  ~ScratchFile() { std::remove(path_.c_str()); }
  // Replaces the file's contents with the input; false if it cannot be written.
  bool write(const uint8_t* data, size_t size) const {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    if (!f) return false;
    bool ok = size == 0 || std::fwrite(data, 1, size, f) == size;
    return std::fclose(f) == 0 && ok;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace penumbra::fuzz
