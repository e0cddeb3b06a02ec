// End-to-end tests of `penumbra converge` (the report's files) and `penumbra render --reference`.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/analysis/reference.h"
#include "core/image/image_io.h"
#include "tests/run_command.h"
#include "tests/test_support.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

std::string analyticScene() {
  return test::sourcePath("scenes/analytic/plane-sphere-light.xml");
}

test::CommandResult penumbraCli(const std::string& args) {
  return test::runCommand("'" PENUMBRA_BINARY "' " + args);
}

TEST(ConvergeCli, ReportFilesExistAndParse) {
  fs::path dir = fs::temp_directory_path() / ("penumbra-converge-" + std::to_string(::getpid()));
  test::CommandResult r = penumbraCli(
      "converge '" + analyticScene() +
      "' --set camera.width=40 --set camera.height=32 --time 0.4 --strategies all --light-selection "
      "all,uniform,power,bvh --light-measure area,solid-angle,projected-solid-angle --heuristic "
      "power,balance -o '" +
      dir.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  // CSV: header with the documented columns, one row per measurement, numbers that parse.
  std::ifstream csv(dir / "convergence.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "strategy,sampler,seconds,cpu_seconds,spp,samples,mse,rmse,rel_mse,mse_stderr,ref_variance,"
            "mse_nolight,rmse_nolight,rel_mse_nolight,mse_stderr_nolight");
  std::set<std::string> strategies;
  int rows = 0;
  for (std::string line; std::getline(csv, line); ++rows) {
    std::stringstream ss(line);
    std::string cell;
    std::getline(ss, cell, ',');
    strategies.insert(cell);
    std::getline(ss, cell, ',');
    EXPECT_EQ(cell, "independent") << line;
    int cols = 2;
    for (; std::getline(ss, cell, ','); ++cols) {
      size_t used = 0;
      double v = std::stod(cell, &used);
      EXPECT_EQ(used, cell.size()) << line;
      EXPECT_TRUE(std::isfinite(v)) << line;
    }
    EXPECT_EQ(cols, 15) << line;
  }
  EXPECT_GE(rows, 21 * 3);  // every measure crossed with every axis: 21 strategies, three measurements each
  EXPECT_EQ(strategies, (std::set<std::string>{"uniform-hemisphere",
                                               "cosine-hemisphere",
                                               "bsdf",
                                               "area",
                                               "area-uniform",
                                               "area-power",
                                               "area-bvh",
                                               "solid-angle",
                                               "solid-angle-uniform",
                                               "solid-angle-power",
                                               "solid-angle-bvh",
                                               "projected-solid-angle",
                                               "projected-solid-angle-uniform",
                                               "projected-solid-angle-power",
                                               "projected-solid-angle-bvh",
                                               "mis-solid-angle-power",
                                               "mis-solid-angle-balance",
                                               "mis-area-power",
                                               "mis-area-balance",
                                               "mis-projected-solid-angle-power",
                                               "mis-projected-solid-angle-balance"}));
  // PNGs decode and have a plausible size.
  for (const char* png : {"convergence.png", "equal-time.png"}) {
    Image img = readImage((dir / png).string());
    EXPECT_GT(img.width, 400) << png;
    EXPECT_GT(img.height, 300) << png;
  }
  std::ifstream md(dir / "summary.md");
  std::string summary((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  for (const char* s : {"| uniform-hemisphere |", "| cosine-hemisphere |", "| area |", "| solid-angle |",
                        "efficiency", "speed-up"})
    EXPECT_NE(summary.find(s), std::string::npos) << s << "\n" << summary;
  fs::remove_all(dir);
}

// --samplers crosses samplers with strategies: every CSV row and summary row names both, and the
// summary gives each pair's fitted slope.
TEST(ConvergeCli, SamplersCrossStrategies) {
  fs::path dir = fs::temp_directory_path() / ("penumbra-converge-samplers-" + std::to_string(::getpid()));
  test::CommandResult r = penumbraCli("converge '" + analyticScene() +
                                      "' --set camera.width=24 --set camera.height=16 --spp 16 --strategies "
                                      "area,solid-angle --samplers independent,sobol,zsobol -o '" +
                                      dir.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  std::ifstream csv(dir / "convergence.csv");
  std::string line;
  std::getline(csv, line);
  std::set<std::string> pairs;
  while (std::getline(csv, line)) pairs.insert(line.substr(0, line.find(',', line.find(',') + 1)));
  EXPECT_EQ(pairs,
            (std::set<std::string>{"area,independent", "area,sobol", "area,zsobol", "solid-angle,independent",
                                   "solid-angle,sobol", "solid-angle,zsobol"}));
  std::ifstream md(dir / "summary.md");
  std::string summary((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  for (const char* s : {"| area | independent |", "| area | sobol |", "| solid-angle | zsobol |", "slope"})
    EXPECT_NE(summary.find(s), std::string::npos) << s << "\n" << summary;
  fs::remove_all(dir);
}

TEST(ConvergeCli, RejectsUnknownSampler) {
  fs::path dir =
      fs::temp_directory_path() / ("penumbra-converge-bogus-sampler-" + std::to_string(::getpid()));
  test::CommandResult r = penumbraCli("converge '" + analyticScene() +
                                      "' --spp 2 --samplers sobol,halton -o '" + dir.string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("unknown sampler 'halton'"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

// Old flattened names still run, with a notice that says how to write them with the axes; the help
// lists the axes' own values only.
TEST(ConvergeCli, OldNamesRunWithANoticeAndHelpListsTheAxes) {
  fs::path dir = fs::temp_directory_path() / ("penumbra-converge-old-" + std::to_string(::getpid()));
  test::CommandResult r = penumbraCli("converge '" + analyticScene() +
                                      "' --set camera.width=8 --set camera.height=8 --spp 2 --strategies "
                                      "solid-angle-bvh -o '" +
                                      dir.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(
      r.out.find("\"solid-angle-bvh\" is an old name; write --strategies solid-angle --light-selection bvh"),
      std::string::npos)
      << r.out;
  std::ifstream csv(dir / "convergence.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(row.substr(0, row.find(',')), "solid-angle-bvh");
  fs::remove_all(dir);
  test::CommandResult help = penumbraCli("converge --help");
  EXPECT_NE(help.out.find("--light-selection"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("--heuristic"), std::string::npos) << help.out;
  EXPECT_EQ(help.out.find("solid-angle-bvh"), std::string::npos) << help.out;
  EXPECT_EQ(help.out.find("mis-area"), std::string::npos) << help.out;
}

TEST(ConvergeCli, RejectsUnknownStrategy) {
  fs::path dir = fs::temp_directory_path() / ("penumbra-converge-bogus-" + std::to_string(::getpid()));
  test::CommandResult r = penumbraCli("converge '" + analyticScene() +
                                      "' --time 0.1 --strategies bogus -o '" + dir.string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("unknown strategy"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

TEST(ConvergeCli, RenderReferenceWritesMeanAndStandardError) {
  fs::path dir = fs::temp_directory_path() / ("penumbra-renderref-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::string out = (dir / "ref.exr").string();
  test::CommandResult r =
      penumbraCli("render --reference '" + test::sourcePath("scenes/hw2/Tests/sphere-area.xml") +
                  "' --set camera.width=24 --set camera.height=16 --spp 8 -o '" + out + "'");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("direct/solid-angle"), std::string::npos) << r.out;  // the lowest-variance estimator
  Reference ref = readReference(out);
  EXPECT_EQ(ref.mean.width, 24);
  ASSERT_EQ(ref.standardError.width, 24);
  EXPECT_NE(ref.source.find("rendered direct/solid-angle 8 spp"), std::string::npos) << ref.source;
  fs::remove_all(dir);
}

// A reference with one infinite or NaN value is refused before anything renders (exit 2), naming the
// count and the first value; nothing is written, and the output directories it would have made (two
// levels here) are not left behind.
TEST(ConvergeCli, NonFiniteReferenceIsRefusedBeforeRendering) {
  const fs::path dir =
      fs::temp_directory_path() / ("penumbra-converge-nonfinite-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const float bad : {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
    Image ref(40, 32);
    for (float& v : ref.rgb) v = 0.5f;
    ref.rgb[ref.index(3, 2) + 1] = bad;
    const std::string path = (dir / "ref.pfm").string(), out = (dir / "new" / "report").string();
    writeImage(path, ref);
    test::CommandResult r = penumbraCli("converge '" + analyticScene() +
                                        "' --set camera.width=40 --set camera.height=32 --spp 4 " +
                                        "--strategies area --reference '" + path + "' -o '" + out + "'");
    EXPECT_EQ(r.exitCode, 2) << r.out;
    EXPECT_NE(r.out.find("reference " + path +
                         ": 1 of 3840 values is not finite; the first at pixel (3, 2) "
                         "channel G: " +
                         (std::isnan(bad) ? "nan" : "inf")),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("RMSE"), std::string::npos) << r.out;  // no run
    EXPECT_FALSE(fs::exists(dir / "new")) << "an empty output directory was left";
  }
  fs::remove_all(dir);
}

// Names in `dir` that look like temporaries (".tmp").
std::vector<std::string> temporariesIn(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".tmp") != std::string::npos) found.push_back(e.path().string());
  return found;
}

// An output the report cannot be written to is found before rendering, and leaves no temporary.
TEST(ConvergeCli, UnwritableOutputIsFoundBeforeRendering) {
  const fs::path dir =
      fs::temp_directory_path() / ("penumbra-converge-unwritable-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "summary.md");  // a directory where the report's file goes
  const std::string run = "converge '" + analyticScene() +
                          "' --set camera.width=40 --set camera.height=32 --spp 4 --strategies area -o ";
  test::CommandResult r = penumbraCli(run + "'" + dir.string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find((dir / "summary.md").string() + ": cannot write: it is a directory"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("RMSE"), std::string::npos) << r.out;
  EXPECT_EQ(temporariesIn(dir), std::vector<std::string>());
  EXPECT_FALSE(fs::exists(dir / "convergence.csv"));
  // A directory in which no file can be created; and a regular file where the directory goes.
  r = penumbraCli(run + "/proc");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("/proc/convergence.csv: cannot create a file in /proc"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("RMSE"), std::string::npos) << r.out;
  std::ofstream(dir / "file") << "x";
  r = penumbraCli(run + "'" + (dir / "file").string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("-o " + (dir / "file").string() + ": exists and is not a directory"),
            std::string::npos)
      << r.out;
  fs::remove_all(dir);
}

// The report's files are written through unique temporaries: none is left, and a second run replaces
// the first run's files.
TEST(ConvergeCli, ReportLeavesNoTemporaries) {
  const fs::path dir = fs::temp_directory_path() / ("penumbra-converge-temps-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string run = "converge '" + analyticScene() +
                          "' --set camera.width=24 --set camera.height=16 --spp 2 --strategies area -o '" +
                          dir.string() + "'";
  for (int i = 0; i < 2; ++i) {
    test::CommandResult r = penumbraCli(run);
    ASSERT_EQ(r.exitCode, 0) << r.out;
  }
  EXPECT_EQ(temporariesIn(dir), std::vector<std::string>());
  for (const char* f : {"convergence.csv", "convergence.png", "equal-time.png", "summary.md"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  fs::remove_all(dir);
}

// Every file in `dir` by name, with its bytes.
std::map<std::string, std::string> filesIn(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    std::ifstream in(e.path(), std::ios::binary);
    files[e.path().filename().string()] =
        std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  return files;
}

// Ctrl-C (SIGINT) while a strategy runs: converge writes its report only after the last run, so a
// previous report in the output directory stays byte-identical and no temporary is left.
TEST(ConvergeCli, InterruptedRunLeavesThePreviousReportAsItWas) {
  const fs::path dir =
      fs::temp_directory_path() / ("penumbra-converge-interrupt-" + std::to_string(::getpid()));
  const std::string log = dir.string() + ".log";
  fs::remove_all(dir);
  const std::string run = "converge '" + analyticScene() +
                          "' --set camera.width=24 --set camera.height=16 --strategies area -o '" +
                          dir.string() + "'";
  test::CommandResult first = penumbraCli(run + " --spp 2");
  ASSERT_EQ(first.exitCode, 0) << first.out;
  const std::map<std::string, std::string> before = filesIn(dir);
  ASSERT_EQ(before.size(), 4u);
  // A 60 s run, interrupted half a second after its reference line (the run has begun). A background
  // job of a shell without job control starts with SIGINT ignored; env restores the terminal's default.
  const test::CommandResult r =
      test::runCommand("env --default-signal=INT '" PENUMBRA_BINARY "' " + run + " --time 60 >'" + log +
                       "' 2>&1 & pid=$!; for i in $(seq 600); do grep -q '^reference: ' '" + log +
                       "' && break; sleep 0.1; done; sleep 0.5; kill -INT $pid; "
                       "( sleep 60; kill -KILL $pid ) >/dev/null 2>&1 & guard=$!; wait $pid; rc=$?; "
                       "kill $guard 2>/dev/null; cat '" +
                       log + "'; echo rc=$rc");
  EXPECT_NE(r.out.find("reference: closed form"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rc=130"), std::string::npos) << r.out;  // ended by the signal
  EXPECT_EQ(r.out.find("wrote "), std::string::npos) << r.out;
  EXPECT_TRUE(filesIn(dir) == before) << "the previous report changed";
  EXPECT_EQ(temporariesIn(dir), std::vector<std::string>());
  fs::remove_all(dir);
  fs::remove(log);
}

}  // namespace
}  // namespace penumbra
