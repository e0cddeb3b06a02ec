// `penumbra check`: runs the stiff-case catalogue (core/analysis/stiff_cases.h) and prints one row
// per case: expected, estimate ± standard error, z-score, NaN/Inf/negative count and verdict.
// Exit code 1 if any case fails, 0 if all pass, 2 for bad arguments (unknown --case).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "app/cli/option_checks.h"
#include "core/analysis/stiff_cases.h"
#include "core/math/error.h"

namespace penumbra::cli {

namespace {

struct CheckOptions {
  std::vector<std::string> cases;
  uint64_t seed = 1;
  bool quick = false;
  bool verbose = false;
  std::string scenes;
};

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

int runCheck(const CheckOptions& o) {
  using namespace analysis;
  std::vector<const StiffCase*> selected;
  for (const StiffCase& c : stiffCases()) {
    bool want = o.cases.empty();
    for (const std::string& name : o.cases) want = want || name == c.name;
    if (want) selected.push_back(&c);
  }
  for (const std::string& name : o.cases) {
    bool known = false;
    for (const StiffCase& c : stiffCases()) known = known || c.name == name;
    if (!known) throw Error("unknown case '" + name + "' (see `penumbra check --list`)");
  }
  CaseOptions co;
  co.seed = o.seed;
  co.quick = o.quick;
  co.sceneDir = o.scenes;

  std::printf("%-24s %-19s %13s %26s %8s %5s  %s\n", "case", "category", "expected", "estimate ± SE", "z",
              "bad", "verdict");
  int failed = 0;
  auto t0 = std::chrono::steady_clock::now();
  for (const StiffCase* c : selected) {
    CaseResult r = runStiffCase(*c, co);
    bool ok = r.passed();
    failed += ok ? 0 : 1;
    std::string est = fmt(r.estimate) + " ± " + fmt(r.standardError);
    std::string z = r.statistical ? fmt(r.zScore()) : "-";
    std::printf("%-24s %-19s %13s %26s %8s %5llu  %s\n", c->name.c_str(), c->category.c_str(),
                fmt(r.expected).c_str(), est.c_str(), z.c_str(), (unsigned long long)r.bad,
                ok ? "PASS" : "FAIL");
    if (o.verbose && !r.note.empty()) std::printf("    %s\n", r.note.c_str());
    for (const std::string& f : r.failures) std::printf("    failure: %s\n", f.c_str());
    std::fflush(stdout);
  }
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%zu cases, %d failed (seed %llu%s, %.1f s)\n", selected.size(), failed,
              (unsigned long long)o.seed, o.quick ? ", quick" : "", secs);
  return failed ? 1 : 0;
}

}  // namespace

void addCheckCommand(CLI::App& app, int& exitCode) {
  auto opts = std::make_shared<CheckOptions>();
  auto list = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "check", "Run the stiff-case catalogue (docs/stiff-cases.md); exit 1 if any case fails");
  cmd->add_option("--case", opts->cases, "Run only this case (repeatable)");
  addSeedOption(*cmd, opts->seed, "Random seed");
  cmd->add_flag("--quick", opts->quick, "Fewer samples per case (a smoke run)");
  cmd->add_flag("-v,--verbose", opts->verbose, "Print what each case compared");
  cmd->add_flag("--list", *list, "List the cases and exit");
  cmd->add_option("--scenes", opts->scenes, "Directory of the stiff scenes (default: scenes/stiff)");
  cmd->callback([opts, list, &exitCode] {
    if (*list) {
      for (const analysis::StiffCase& c : analysis::stiffCases())
        std::printf("%-24s %-19s  %s\n", c.name.c_str(), c.category.c_str(), c.description.c_str());
      exitCode = 0;
      return;
    }
    exitCode = runCheck(*opts);
  });
}

}  // namespace penumbra::cli
