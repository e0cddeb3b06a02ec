#include "app/platform/offscreen_exec.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "app/platform/platform.h"
#include "core/math/error.h"

namespace penumbra::platform {

std::string offscreenBinary() {
  std::error_code ec;
  std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("cannot locate the penumbra executable (/proc/self/exe): " + ec.message());
  return (self.parent_path() / "penumbra-offscreen").string();
}

void execOffscreen(const std::vector<std::string>& args) {
  std::string bin = offscreenBinary();
  std::vector<std::string> all = {bin};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  execv(bin.c_str(), argv.data());
  throw Error("cannot run " + bin + " for offscreen rendering: " + std::strerror(errno));
}

void runOffscreenUnlessWindowed(const char* command, bool offscreen, const std::string& output,
                                const std::function<std::vector<std::string>()>& offscreenArgs) {
  if (isOffscreenBuild()) return;
  std::string why;
  if (!offscreen && !displayAvailable(why)) {
    std::fprintf(stderr, "%s: %s; rendering offscreen instead (OSMesa) and writing %s\n", command,
                 why.c_str(), output.c_str());
    offscreen = true;
  }
  if (offscreen) execOffscreen(offscreenArgs());
}

}  // namespace penumbra::platform
