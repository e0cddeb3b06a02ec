#include "core/image/atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstring>

#include "core/math/bounded_read.h"
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

std::string directoryOf(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string baseNameOf(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// "<pid>-<n>" with both parts decimal: the pid; 0 if `rest` is not of that form.
long tempOwnerPid(std::string_view rest) {
  const auto dash = rest.find('-');
  if (dash == 0 || dash == std::string_view::npos || dash + 1 == rest.size()) return 0;
  long pid = 0;
  unsigned long n = 0;
  auto [p1, e1] = std::from_chars(rest.data(), rest.data() + dash, pid);
  auto [p2, e2] = std::from_chars(rest.data() + dash + 1, rest.data() + rest.size(), n);
  if (e1 != std::errc() || p1 != rest.data() + dash || e2 != std::errc() || p2 != rest.data() + rest.size())
    return 0;
  return pid > 0 ? pid : 0;
}

// Best effort: make the rename itself durable. Failure here does not undo a completed write.
void syncParentDirectory(const std::string& path) {
  const std::string dir = directoryOf(path);
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

void checkOutputPath(const std::string& path) {
  if (path.empty()) throw Error("cannot write image: empty output path");
  checkNoNulInPath(path, "output");
  const std::string dir = directoryOf(path);
  struct stat st;
  if (::stat(dir.c_str(), &st) != 0) {
    const int err = errno;
    throw Error(path, 0, "cannot write: directory " + dir + ": " + errnoText(err));
  }
  if (!S_ISDIR(st.st_mode)) throw Error(path, 0, "cannot write: " + dir + " is not a directory");
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw Error(path, 0, "cannot write: it is a directory");
    if (!S_ISREG(st.st_mode)) throw Error(path, 0, "cannot write: it exists and is not a regular file");
    // The mode bits, not access(): root may write anything, but a read-only output is protected.
    if ((st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || ::access(path.c_str(), W_OK) != 0)
      throw Error(
          path, 0,
          "cannot write: the existing file is read-only (left unchanged; make it writable or remove it)");
  }
  // The only reliable test of "can a file be created here" (permissions, read-only or special file
  // systems such as /proc) is to create one.
  const std::string probe = atomicTempPath(path);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int err = errno;
    throw Error(path, 0, "cannot create a file in " + dir + ": " + errnoText(err));
  }
  ::close(fd);
  removeQuietly(probe);
}

int removeStaleTemporaries(const std::string& path) {
  const std::string prefix = baseNameOf(path) + ".tmp-";
  DIR* d = ::opendir(directoryOf(path).c_str());
  if (!d) return 0;
  int removed = 0;
  const long self = static_cast<long>(::getpid());
  while (const dirent* e = ::readdir(d)) {
    std::string_view name(e->d_name);
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const long pid = tempOwnerPid(name.substr(prefix.size()));
    if (pid == 0 || pid == self) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to judge)
    const std::string stale = directoryOf(path) + "/" + std::string(name);
    struct stat st;
    if (::lstat(stale.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::unlink(stale.c_str()) == 0) ++removed;
  }
  ::closedir(d);
  return removed;
}

void writeFileAtomically(const std::string& path,
                         const std::function<void(const std::string& tempPath)>& write) {
  checkOutputPath(path);
  removeStaleTemporaries(path);
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
