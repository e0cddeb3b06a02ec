// Issue 6: references, error against time, and the `penumbra converge` report.
//
// Timing and flakiness. The machine these tests run on is shared (other builds compete for the two
// cores: load average 7-8 while this was written), so wall-clock throughput drifts by 1.5-2x within
// seconds. Measured on the analytic scene, the fitted slope of log MSE against log *wall* time
// scattered over [-1.15, -0.88] between runs while the slope against spp was -1.00 +- 0.007: all the
// scatter is throughput drift, none is the estimator. Hence:
//  - The slope test uses the render's CPU time (ConvergencePoint::cpuSeconds: process CPU at each
//    pass boundary minus the polling thread's own), which does not advance while other processes
//    hold the cores. It fits from 20 ms (and >= 8 passes: start-up and per-pass overheads make the
//    very first passes slower per sample) to 2 s, two decades, on an image large enough that a pass
//    takes milliseconds. Slopes observed: -0.98 .. -1.03; the accepted range is the issue's
//    [-1.15, -0.85]. The wall-time slope is printed for information, not asserted.
//  - The ranking test compares strategies at equal CPU time: each renders the same spp
//    (deterministic given the seed) and the equal-time MSE is MSE(N) * cpu(N) / budget, i.e. the
//    ranking is by MSE * CPU seconds = 1/efficiency. (MSE at equal time scales as MSE * cost for an
//    unbiased estimator because MSE is proportional to 1/spp, which the slope test checks.)
//  - Rankings use the metric over pixels that see no light: pixels at the light's silhouette have a
//    large variance from the pixel filter alone (300 vs 0.1 within one footprint), the same for
//    every light-sampling strategy, and at 64x64 it is ~99.9% of the all-pixel MSE.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "app/ui/convergence_tracker.h"
#include "core/analysis/convergence.h"
#include "core/analysis/reference.h"
#include "core/image/image_io.h"
#include "tests/test_support.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

std::string analyticScene() {
  return test::sourcePath("scenes/analytic/plane-sphere-light.xml");
}
std::string sphereScene() {
  return test::sourcePath("scenes/hw2/Tests/sphere-area.xml");
}

LoadedScene loadSmall(const std::string& path, int size) {
  return loadScene(path, {{"camera.width", std::to_string(size)}, {"camera.height", std::to_string(size)}});
}

TEST(Reference, ClosedFormAgreesWithRendering) {
  // The closed form of the analytic scene against a rendered solid-angle reference: the normalised
  // squared difference averages to ~1 (a chi-square per pixel) if both are right.
  LoadedScene scene = loadSmall(analyticScene(), 32);
  ASSERT_TRUE(hasClosedFormReference(scene));
  Reference exact = closedFormReference(scene);
  Reference rendered = renderReference(scene, RenderLimits{512, 0}, 0, 7);
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < exact.mean.rgb.size(); i += 3) {
    double se = rendered.standardError.rgb[i];
    ASSERT_GT(se, 0.0);
    double z = (rendered.mean.rgb[i] - exact.mean.rgb[i]) / se;
    sum += z * z;
    ++n;
  }
  double chi2 = sum / n;  // E = 1, sd ≈ sqrt(2/n) ≈ 0.04 for Gaussian z (standard errors are estimated)
  EXPECT_GT(chi2, 0.75);
  EXPECT_LT(chi2, 1.3);
  EXPECT_GT(exact.mean.rgb[3 * (16 * 32 + 16)], 0.1f);  // the plane is lit
}

TEST(Reference, HashIgnoresEstimatorSettingsOnly) {
  LoadedScene a = loadScene(sphereScene());
  LoadedScene b =
      loadScene(sphereScene(), {{"integrator.measure", "solid-angle"}, {"sampler.sampleCount", "3"}});
  LoadedScene c = loadScene(sphereScene(), {{"camera.width", "64"}});
  EXPECT_EQ(sceneContentHash(a.desc), sceneContentHash(b.desc));
  EXPECT_NE(sceneContentHash(a.desc), sceneContentHash(c.desc));
  EXPECT_NE(referenceCachePath(a).find(".ref-"), std::string::npos);
}

TEST(Reference, CacheRoundTripAndMask) {
  fs::path dir = fs::temp_directory_path() / ("penumbra-ref-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  LoadedScene scene = loadSmall(sphereScene(), 24);
  ReferenceRequest rq;
  rq.cacheDir = dir.string();
  rq.referenceSpp = 16;
  Reference r1 = obtainReference(scene, rq);
  ASSERT_TRUE(fs::exists(referenceCachePath(scene, dir.string())));
  ASSERT_TRUE(fs::exists(standardErrorPath(referenceCachePath(scene, dir.string()))));
  Reference r2 = obtainReference(scene, rq);  // from the cache now
  EXPECT_EQ(r2.source.rfind("cache", 0), 0u) << r2.source;
  EXPECT_EQ(r1.mean.rgb, r2.mean.rgb);
  EXPECT_EQ(r1.standardError.rgb, r2.standardError.rgb);
  // The light is in view: some pixels are masked, most are not.
  std::vector<uint8_t> mask = emitterMask(scene);
  std::size_t lit = 0;
  for (uint8_t m : mask) lit += m;
  EXPECT_GT(lit, 0u);
  EXPECT_LT(lit, mask.size() / 4);
  fs::remove_all(dir);
}

TEST(Convergence, MseSlopeAgainstTimeOnAnalyticScene) {
  // 80x80: a pass (~3 ms) is long against the fixed per-pass cost (barrier, snapshot), which
  // otherwise makes early passes slower per sample and flattens the fitted slope.
  LoadedScene scene = loadSmall(analyticScene(), 80);
  Reference ref = closedFormReference(scene);
  std::vector<uint8_t> mask = emitterMask(scene);
  ConvergenceOptions o;
  o.seconds = 2;
  o.seed = 3;
  for (const IntegratorDesc& d : parseStrategies(scene.settings.integrator, "all")) {
    ConvergenceRun run = runConvergence(scene, d, ref, mask, o);
    std::vector<double> t, cpu, mse, spp;
    for (const ConvergencePoint& p : run.points)
      if (p.seconds >= 0.02 && p.spp >= 8)
        t.push_back(p.seconds), cpu.push_back(p.cpuSeconds), mse.push_back(p.error.all.mse),
            spp.push_back(p.spp);
    ASSERT_GE(t.size(), 5u) << run.strategy;
    double slope = logLogSlope(cpu, mse);
    EXPECT_GE(slope, -1.15) << run.strategy;
    EXPECT_LE(slope, -0.85) << run.strategy;
    // Against wall time and spp for diagnosis: spp separates sampling noise from throughput drift.
    std::printf("%-28s slope %.3f against CPU time over %zu points (wall time %.3f, spp %.3f), %u spp\n",
                run.strategy.c_str(), slope, t.size(), logLogSlope(t, mse), logLogSlope(spp, mse), run.spp);
  }
}

TEST(Convergence, EqualTimeRankingOnSphereScene) {
  LoadedScene scene = loadSmall(sphereScene(), 64);
  Reference ref = renderReference(scene, RenderLimits{2048, 0});  // kReferenceSeed: independent of 1, 2, 3
  std::vector<uint8_t> mask = emitterMask(scene);
  std::vector<IntegratorDesc> order =
      parseStrategies(scene.settings.integrator, "solid-angle,area,cosine-hemisphere,uniform-hemisphere");
  for (uint64_t seed : {1, 2, 3}) {
    std::vector<double> score;  // MSE * CPU seconds: equal-CPU-time MSE up to a common factor
    for (const IntegratorDesc& d : order) {
      ConvergenceOptions o;
      o.spp = 128;
      o.seed = seed;
      ConvergenceRun run = runConvergence(scene, d, ref, mask, o);
      double cpu = run.points.back().cpuSeconds;
      score.push_back(run.points.back().error.noLight.mse * cpu);
      std::printf("seed %llu %-28s MSE %.4e (all px %.4e) cpu %.3f s -> %.4e\n", (unsigned long long)seed,
                  run.strategy.c_str(), run.points.back().error.noLight.mse, run.points.back().error.all.mse,
                  cpu, score.back());
    }
    for (std::size_t i = 0; i + 1 < score.size(); ++i)
      EXPECT_LT(score[i], score[i + 1])
          << "seed " << seed << ": " << strategyLabel(order[i]) << " vs " << strategyLabel(order[i + 1]);
  }
}

struct CliRun {
  int exitCode;
  std::string out;
};
CliRun penumbraCli(const std::string& args) {
  std::string cmd = "'" PENUMBRA_BINARY "' " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return {-1, ""};
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

TEST(ConvergeCli, ReportFilesExistAndParse) {
  fs::path dir = fs::temp_directory_path() / ("penumbra-converge-" + std::to_string(::getpid()));
  CliRun r = penumbraCli("converge '" + analyticScene() +
                         "' --set camera.width=40 --set camera.height=32 --time 0.4 --strategies all -o '" +
                         dir.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  // CSV: header with the documented columns, one row per measurement, numbers that parse.
  std::ifstream csv(dir / "convergence.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "strategy,seconds,cpu_seconds,spp,samples,mse,rmse,rel_mse,mse_stderr,ref_variance,"
            "mse_nolight,rmse_nolight,rel_mse_nolight,mse_stderr_nolight");
  std::set<std::string> strategies;
  int rows = 0;
  for (std::string line; std::getline(csv, line); ++rows) {
    std::stringstream ss(line);
    std::string cell;
    std::getline(ss, cell, ',');
    strategies.insert(cell);
    int cols = 1;
    for (; std::getline(ss, cell, ','); ++cols) {
      size_t used = 0;
      double v = std::stod(cell, &used);
      EXPECT_EQ(used, cell.size()) << line;
      EXPECT_TRUE(std::isfinite(v)) << line;
    }
    EXPECT_EQ(cols, 14) << line;
  }
  EXPECT_GE(rows, 4 * 3);
  EXPECT_EQ(strategies,
            (std::set<std::string>{"uniform-hemisphere", "cosine-hemisphere", "area", "solid-angle"}));
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

TEST(ConvergeCli, RejectsUnknownStrategy) {
  CliRun r =
      penumbraCli("converge '" + analyticScene() + "' --time 0.1 --strategies bogus -o /tmp/penumbra-x");
  EXPECT_EQ(r.exitCode, 2) << r.out;
  EXPECT_NE(r.out.find("unknown strategy"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// The viewer's live tracker (no GL): one curve per accumulation, kept across strategy switches.
TEST(ConvergenceTracker, KeepsOneCurvePerStrategy) {
  LoadedScene scene = loadScene(test::sourcePath("scenes/analytic/plane-sphere-light.xml"),
                                {{"camera.width", "48"}, {"camera.height", "48"}});
  ui::ViewerController c(std::move(scene), {}, 2);
  ui::ConvergenceTracker t;
  RenderSettings s = c.settings();
  s.integrator.strategy = Strategy::DirectArea;
  c.setSettings(s);
  c.setLimits(RenderLimits{256, 0});
  c.start();
  auto drive = [&] {
    for (int i = 0; i < 4000 && !(c.progress().finished && c.snapshot().spp == c.progress().spp); ++i) {
      c.pollSnapshot(false);
      t.update(c);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    c.pollSnapshot(false);
    t.update(c);
  };
  drive();
  ASSERT_TRUE(t.hasReference()) << t.error();
  EXPECT_EQ(t.reference().source, "closed-form");
  ASSERT_EQ(t.curves().size(), 1u);
  s.integrator.strategy = Strategy::DirectSolidAngle;
  c.setSettings(s);
  c.start();
  drive();
  ASSERT_EQ(t.curves().size(), 2u);
  EXPECT_EQ(t.curves()[0].label, "direct/area");
  EXPECT_EQ(t.curves()[1].label, "direct/solid-angle");
  for (const ui::ConvergenceCurve& curve : t.curves()) {
    ASSERT_GE(curve.rmse.size(), 3u) << curve.label;
    EXPECT_LT(curve.rmse.back(), curve.rmse.front()) << curve.label;  // a few spp -> 256 spp
  }
  // Solid-angle sampling beats area sampling on this scene by far at equal spp.
  EXPECT_LT(t.curves()[1].rmse.back(), t.curves()[0].rmse.back());
  // A reference of the wrong size is refused with a message.
  std::string bad = (fs::temp_directory_path() / "penumbra-bad-ref.pfm").string();
  writeImage(bad, Image(8, 8));
  EXPECT_FALSE(t.loadReference(c, bad));
  EXPECT_NE(t.error().find("8x8"), std::string::npos) << t.error();
  fs::remove(bad);
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

TEST(ConvergeCli, RenderReferenceWritesMeanAndStandardError) {
  fs::path dir = fs::temp_directory_path() / ("penumbra-renderref-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::string out = (dir / "ref.exr").string();
  CliRun r = penumbraCli("render --reference '" + test::sourcePath("scenes/hw2/Tests/sphere-area.xml") +
                         "' --set camera.width=24 --set camera.height=16 --spp 8 -o '" + out + "'");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("direct/solid-angle"), std::string::npos) << r.out;  // the lowest-variance estimator
  Reference ref = readReference(out);
  EXPECT_EQ(ref.mean.width, 24);
  ASSERT_EQ(ref.standardError.width, 24);
  EXPECT_NE(ref.source.find("rendered direct/solid-angle 8 spp"), std::string::npos) << ref.source;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace penumbra
