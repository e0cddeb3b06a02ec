// Runs a shell command for end-to-end tests, capturing its exit code and its output (stderr merged).
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

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

}  // namespace penumbra::test
