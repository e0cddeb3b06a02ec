// End-to-end tests of `penumbra check` (the stiff-case catalogue) and of bad-value scenes in
// `penumbra render`: exit codes, the table, and no image written for rejected scenes.
#include <gtest/gtest.h>

#include "tests/run_command.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "core/analysis/stiff_cases.h"

namespace {

using CliRun = penumbra::test::CommandResult;

// Runs `penumbra <args>` through the shell (stderr merged into the output).
CliRun penumbra(const std::string& args) {
  return penumbra::test::runCommand("'" PENUMBRA_BINARY "' " + args);
}

const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/stiff";

TEST(CheckCli, QuickRunPassesAndPrintsEveryCase) {
  CliRun r = penumbra("check --quick --scenes '" + kScenes + "'");
  EXPECT_EQ(r.exitCode, 0) << r.out;
  for (const char* column : {"case", "category", "expected", "estimate ± SE", "z", "bad", "verdict"})
    EXPECT_NE(r.out.find(column), std::string::npos) << column;
  for (const auto& c : penumbra::analysis::stiffCases()) {
    size_t at = r.out.find("\n" + c.name + " ");
    ASSERT_NE(at, std::string::npos) << c.name << " missing from\n" << r.out;
    size_t eol = r.out.find('\n', at + 1);
    const std::string row = r.out.substr(at, eol - at);
    EXPECT_NE(row.find(" " + c.category + " "), std::string::npos) << row;
    EXPECT_NE(row.find("PASS"), std::string::npos) << row;
  }
  EXPECT_EQ(r.out.find("FAIL"), std::string::npos) << r.out;
}

TEST(CheckCli, AFailingCaseExitsWithOne) {
  // A copy of the scenes where a bad-value scene has been "fixed": it is accepted, so the case fails.
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / ("penumbra-check-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::copy(kScenes, dir, fs::copy_options::recursive);
  fs::copy_file(dir / "radiance-0.xml", dir / "bad-nan.xml", fs::copy_options::overwrite_existing);
  CliRun r = penumbra("check --case bad-values --scenes '" + dir.string() + "'");
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_NE(r.out.find("FAIL"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("bad-nan.xml was accepted"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

TEST(CheckCli, SelectsCasesAndRejectsUnknownOnes) {
  CliRun r = penumbra("check --case film-1e6-samples --case warp-extremes --scenes '" + kScenes + "'");
  EXPECT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("film-1e6-samples"), std::string::npos);
  EXPECT_EQ(r.out.find("scale-ao"), std::string::npos);
  EXPECT_EQ(penumbra("check --case no-such-case").exitCode, 2);
  CliRun list = penumbra("check --list");
  EXPECT_EQ(list.exitCode, 0);
  EXPECT_NE(list.out.find("cone-sin2-1e-12"), std::string::npos);
  EXPECT_NE(list.out.find("narrow-cone"), std::string::npos) << list.out;
}

TEST(CheckCli, BadValueScenesAreRejectedAndWriteNoImage) {
  namespace fs = std::filesystem;
  fs::path out = fs::temp_directory_path() / ("penumbra-bad-" + std::to_string(::getpid()) + ".pfm");
  for (const char* file :
       {"bad-nan.xml", "bad-inf.xml", "bad-1e999.xml", "bad-sampleCount-0.xml", "bad-sampleCount--4.xml",
        "bad-sampleCount-4294967296.xml", "bad-sampleCount-3.5.xml", "bad-fov-0.xml", "bad-fov-180.xml"}) {
    fs::remove(out);
    CliRun r = penumbra("render '" + kScenes + "/" + file + "' -o '" + out.string() + "' --spp 1");
    EXPECT_EQ(r.exitCode, 2) << file << ": " << r.out;
    EXPECT_NE(r.out.find(std::string(file) + ":"), std::string::npos) << "no file:line in: " << r.out;
    EXPECT_FALSE(fs::exists(out)) << file << " wrote an image";
  }
}

}  // namespace
