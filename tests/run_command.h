// Runs a shell command for end-to-end tests, capturing its exit code and its output (stderr merged).
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

namespace penumbra::test {

struct CommandResult {
  int exitCode = -1;
  std::string out;
};

inline CommandResult runCommand(const std::string& cmd) {
  CommandResult r;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  int status = pclose(p);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Runs `command` (a program that opens a GLFW window) under xvfb-run with a 1024x768 screen until its
// output shows it ran in a real window, at most five times: xvfb-run -a can race an X server starting
// elsewhere at the same moment (parallel ctest, other test runs on the machine). The display numbers
// start from `firstDisplay` plus a spread by process id and move on at every attempt.
inline CommandResult runUnderXvfb(const std::string& command, int firstDisplay) {
  CommandResult r;
  const int base = firstDisplay + int(::getpid() % 97) * 11;
  for (int attempt = 0; attempt < 5; ++attempt) {
    if (attempt > 0) std::this_thread::sleep_for(std::chrono::milliseconds(300 * attempt));
    r = runCommand("xvfb-run -a -n " + std::to_string(base + 7 * attempt) + " -s '-screen 0 1024x768x24' " +
                   command);
    if (r.exitCode == 0 && r.out.find("GLFW") != std::string::npos) break;
  }
  return r;
}

}  // namespace penumbra::test
