#include "core/math/bounded_read.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/math/error.h"

namespace penumbra {

namespace {

std::string sizeText(uint64_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f MB", double(bytes) / double(1 << 20));
  return buf;
}

}  // namespace

void checkNoNulInPath(const std::string& path, const std::string& what) {
  const size_t nul = path.find('\0');
  if (nul == std::string::npos) return;
  std::string shown;
  for (char c : path) shown += c == '\0' ? std::string("\\0") : std::string(1, c);
  throw Error(what + " path \"" + shown + "\" has a NUL byte at offset " + std::to_string(nul) +
              ": no file can have that name");
}

void checkRegularFile(const std::string& path, uint64_t maxBytes, const std::string& what) {
  checkNoNulInPath(path, what);
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    throw Error(path, 0, "cannot open " + what + ": " + std::strerror(err));
  }
  if (S_ISDIR(st.st_mode)) throw Error(path, 0, "cannot read " + what + ": it is a directory");
  if (!S_ISREG(st.st_mode)) throw Error(path, 0, "cannot read " + what + ": not a regular file");
  if (uint64_t(st.st_size) > maxBytes)
    throw Error(path, 0,
                what + " of " + sizeText(uint64_t(st.st_size)) + " is larger than the limit of " +
                    sizeText(maxBytes));
}

std::string readRegularFile(const std::string& path, uint64_t maxBytes, const std::string& what) {
  checkRegularFile(path, maxBytes, what);
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    const int err = errno;
    throw Error(path, 0, "cannot open " + what + ": " + std::strerror(err));
  }
  std::string bytes;
  char buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) {
    if (bytes.size() + n > maxBytes) {
      std::fclose(f);
      throw Error(path, 0, what + " grew beyond the limit of " + sizeText(maxBytes) + " while being read");
    }
    bytes.append(buf, n);
  }
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) throw Error(path, 0, "read error in " + what);
  return bytes;
}

}  // namespace penumbra
