#include "core/image/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include "core/math/error.h"

namespace penumbra {

namespace {

std::atomic<unsigned long> gTempCounter{0};

std::string errnoText(int err) {
  return std::strerror(err);
}

void removeQuietly(const std::string& p) {
  int saved = errno;
  ::unlink(p.c_str());
  errno = saved;
}

// fsync the file's data to disk; throws with strerror on failure.
void syncFile(const std::string& tempPath, const std::string& path) {
  int fd = ::open(tempPath.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    throw Error(path, 0, "cannot reopen temporary file " + tempPath + ": " + errnoText(err));
  }
  int rc = ::fsync(fd);
  int err = errno;
  ::close(fd);
  if (rc != 0) throw Error(path, 0, "fsync failed: " + errnoText(err));
}

// Best effort: make the rename itself durable. Failure here does not undo a completed write.
void syncParentDirectory(const std::string& path) {
  std::string dir = ".";
  if (auto slash = path.find_last_of('/'); slash != std::string::npos)
    dir = slash == 0 ? "/" : path.substr(0, slash);
  int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

std::string atomicTempPath(const std::string& path) {
  return path + ".tmp-" + std::to_string(static_cast<long>(::getpid())) + "-" +
         std::to_string(gTempCounter.fetch_add(1, std::memory_order_relaxed));
}

void writeFileAtomically(const std::string& path,
                         const std::function<void(const std::string& tempPath)>& write) {
  if (path.empty()) throw Error("cannot write image: empty output path");
  const std::string temp = atomicTempPath(path);
  try {
    write(temp);
    syncFile(temp, path);
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
      const int err = errno;
      throw Error(path, 0, "cannot rename " + temp + " onto it: " + errnoText(err));
    }
  } catch (...) {
    removeQuietly(temp);
    throw;
  }
  syncParentDirectory(path);
}

void writeStdioAtomically(const std::string& path, const std::function<void(std::FILE*)>& write) {
  writeFileAtomically(path, [&](const std::string& temp) {
    std::FILE* f = std::fopen(temp.c_str(), "wb");
    if (!f) {
      const int err = errno;
      throw Error(path, 0, "cannot create " + temp + ": " + errnoText(err));
    }
    try {
      write(f);
    } catch (...) {
      std::fclose(f);
      throw;
    }
    bool bad = std::ferror(f) != 0;
    int err = bad ? errno : 0;
    if (std::fflush(f) != 0) {
      bad = true;
      err = errno;
    }
    if (std::fclose(f) != 0 && !bad) {
      bad = true;
      err = errno;
    }
    if (bad) throw Error(path, 0, "write failed: " + errnoText(err ? err : EIO));
  });
}

void writeBytesAtomically(const std::string& path, const void* data, std::size_t size) {
  writeStdioAtomically(path, [&](std::FILE* f) {
    if (size > 0 && std::fwrite(data, 1, size, f) != size) {
      const int err = errno ? errno : EIO;
      throw Error(path, 0, "write failed: " + errnoText(err));
    }
  });
}

}  // namespace penumbra
