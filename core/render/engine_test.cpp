#include "core/render/engine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>
#include <thread>

#include "core/geometry/procedural_mesh.h"
#include "core/math/error.h"
#include "core/math/frame.h"
#include "core/sampling/sampler_table.h"

namespace penumbra {
namespace {

// Polls until `done()` or two seconds pass (the machine may be busy): tests never assume timings.
template <class F>
bool eventually(F done) {
  for (int i = 0; i < 400; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

// A diffuse unit sphere on a ground plane (z = -1), lit by a small bright sphere light: soft shadows
// and light sampling noise, so pixels differ in mean and in standard error.
std::shared_ptr<const Scene> smallScene() {
  auto scene = std::make_shared<Scene>();
  SphereLight light;
  light.sphere = Sphere{Vec3(1.f, -1.5f, 1.75f), 0.1f};
  light.radiance = Color3(300.f);
  SurfaceMaterial emitter;
  emitter.sphereLight = 0;
  light.geometryIndex = int32_t(scene->geometry.addSphere(light.sphere, 0));
  scene->sphereLights.push_back(light);
  scene->materials.push_back(emitter);
  scene->geometry.addSphere(Sphere{Vec3(0.f), 1.f}, 1);
  scene->materials.push_back(SurfaceMaterial{});
  scene->geometry.addMesh(makeGridPlane(Vec3(-100, -100, -1), Vec3(200, 0, 0), Vec3(0, 200, 0), 1, 1), 2);
  scene->materials.push_back(SurfaceMaterial{});
  scene->geometry.build();
  scene->rayLengthBound = scene->geometry.bounds().diagonal() * 1.01f;
  return scene;
}

// 48 x 32 pixels of that scene, direct lighting with the default strategy.
std::shared_ptr<RenderJob> smallJob() {
  RenderSettings s;
  CameraDesc& cam = s.camera;
  const Vec3 origin(4, 4, 0), dir = glm::normalize(Vec3(0.f) - origin);
  const Vec3 left = glm::normalize(glm::cross(Vec3(0, 0, 1), dir));
  cam.toWorld = cameraToWorld(origin, left, glm::cross(dir, left), dir);
  cam.fovDegrees = 40.f;
  cam.width = 48;
  cam.height = 32;
  s.sampleCount = 64;
  s.seed = 42;
  return std::make_shared<RenderJob>(smallScene(), s, RenderLimits{});
}

// One row whose 4096 pixels each take 65536 light samples: tens of seconds for the row, milliseconds
// per pixel.
std::shared_ptr<RenderJob> expensiveRowJob() {
  auto job = smallJob();
  job->settings.camera.width = 4096;
  job->settings.camera.height = 1;
  job->settings.integrator.samples = 65536;
  return job;
}

Image render(std::shared_ptr<RenderJob> job, uint32_t spp, int threads) {
  Engine engine;
  engine.start(job, RenderLimits{spp, 0.0}, threads);
  engine.wait();
  EXPECT_EQ(engine.progress().spp, spp);
  EXPECT_TRUE(engine.progress().finished);
  return engine.film().mean(spp);
}

TEST(Engine, ImageDoesNotDependOnThreadCount) {
  auto job = smallJob();
  Image a = render(job, 8, 1), b = render(job, 8, 2), c = render(job, 8, 5);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  EXPECT_EQ(a.rgb, b.rgb);  // bitwise
  EXPECT_EQ(a.rgb, c.rgb);
}

// The writer of a finished render takes its image from the last snapshot (resolved row by row by the
// workers when the pass target is known) instead of resolving the film again.
TEST(Engine, TheLastSnapshotIsTheFinalImage) {
  auto job = smallJob();
  for (const uint32_t spp : {1u, 3u}) {
    for (const bool withError : {false, true}) {
      Engine engine;
      engine.start(job, RenderLimits{spp, 0.0}, 2);
      if (withError) engine.requestSnapshot(true);
      engine.wait();
      FilmSnapshot last;
      ASSERT_TRUE(engine.takeSnapshot(last));
      EXPECT_EQ(last.spp, spp);
      EXPECT_EQ(last.mean.rgb, engine.film().mean(spp).rgb);  // bitwise
      if (withError && spp >= 2) {
        EXPECT_EQ(last.standardError.rgb, engine.film().standardError(spp).rgb);
      }
    }
  }
}

TEST(Engine, SeedChangesTheImage) {
  auto job = smallJob();
  Image a = render(job, 4, 2);
  auto other = std::make_shared<RenderJob>(*job);
  other->settings.seed = 43;
  Image b = render(other, 4, 2);
  EXPECT_NE(a.rgb, b.rgb);
}

TEST(Engine, SnapshotsCarryTheProbePixelsStatistics) {
  auto job = smallJob();
  // A pixel whose samples vary (soft shadow or light sampling noise), found by a first render.
  int px = -1, py = -1;
  {
    Engine first;
    first.start(job, RenderLimits{6, 0.0}, 2);
    first.wait();
    Image err = first.film().standardError(6);
    for (int y = 0; y < err.height && px < 0; ++y)
      for (int x = 0; x < err.width && px < 0; ++x)
        if (err.at(x, y).x > 0.f) px = x, py = y;
  }
  ASSERT_GE(px, 0);
  Engine engine;
  engine.setProbePixel(px, py);
  engine.start(job, RenderLimits{6, 0.0}, 2);
  for (int i = 0; i < 3; ++i) engine.requestSnapshot();
  engine.wait();
  FilmSnapshot snap;
  ASSERT_TRUE(engine.takeSnapshot(snap));  // the viewer's way (latestSnapshot copies the same fields)
  ASSERT_EQ(snap.spp, 6u);
  EXPECT_EQ(snap.probe.x, px);
  EXPECT_EQ(snap.probe.y, py);
  Color3 mean, se;
  engine.film().pixelStatistics(6, px, py, mean, se);
  EXPECT_EQ(snap.probe.mean, mean);
  EXPECT_EQ(snap.probe.standardError, se);
  EXPECT_EQ(snap.probe.mean, snap.mean.at(px, py));
  EXPECT_TRUE(snap.standardError.empty());  // no whole-image resolve was asked for
  EXPECT_GT(se.x + se.y + se.z, 0.f);

  // At rest (finished) any pixel can be read at once; out of the image there is nothing.
  FilmSnapshot::Probe probe;
  ASSERT_TRUE(engine.probeAtRest(3, 2, probe));
  engine.film().pixelStatistics(6, 3, 2, mean, se);
  EXPECT_EQ(probe.mean, mean);
  EXPECT_FALSE(engine.probeAtRest(48, 0, probe));
  engine.setProbePixel(-1, 0);
}

TEST(Engine, ProbeWaitsWhileTheFilmIsBeingWritten) {
  auto job = smallJob();
  Engine engine;
  engine.start(job, RenderLimits{0, 0.0}, 2);  // unlimited: running until cancelled
  FilmSnapshot::Probe probe;
  EXPECT_FALSE(engine.probeAtRest(1, 1, probe));
  engine.setPaused(true);
  // Paused takes effect at the next pass boundary; then the film is at rest.
  EXPECT_TRUE(eventually([&] { return engine.probeAtRest(1, 1, probe); }));
  EXPECT_EQ(probe.x, 1);
  // No snapshot was requested: the resting pass is published on demand, once.
  FilmSnapshot snap;
  engine.latestSnapshot(snap);
  EXPECT_NE(snap.spp, engine.progress().spp);
  EXPECT_TRUE(engine.publishAtRest());
  EXPECT_FALSE(engine.publishAtRest());
  ASSERT_TRUE(engine.latestSnapshot(snap));
  EXPECT_EQ(snap.spp, engine.progress().spp);
  engine.cancel();
  EXPECT_FALSE(engine.publishAtRest());
}

TEST(Engine, PassSecondsTimeEachBoundary) {
  auto job = smallJob();
  Engine engine;
  engine.start(job, RenderLimits{5, 0.0}, 2);
  engine.wait();
  RenderProgress p = engine.progress();
  EXPECT_EQ(p.spp, 5u);
  EXPECT_GT(p.passSeconds, 0.0);
  EXPECT_LE(p.passSeconds, p.seconds);
}

TEST(Engine, CancelStopsQuicklyAndRestartBeginsAtZero) {
  auto job = smallJob();
  Engine engine;
  engine.start(job, RenderLimits{}, 2);  // unlimited
  ASSERT_TRUE(eventually([&] { return engine.progress().spp > 0; }));
  auto t0 = std::chrono::steady_clock::now();
  engine.cancel();
  double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(ms, 1000.0);  // generous: a row takes well under a millisecond; this only catches hangs
  EXPECT_TRUE(engine.progress().finished);
  uint32_t before = engine.progress().spp;
  EXPECT_GT(before, 0u);
  engine.start(job, RenderLimits{3, 0.0}, 2);
  engine.wait();
  EXPECT_EQ(engine.progress().spp, 3u);
}

TEST(Engine, CancelReachesInsideARowOfExpensivePixels) {
  // Cancelling must not wait for the row (tens of seconds).
  auto job = expensiveRowJob();
  Engine engine;
  engine.start(job, RenderLimits{}, 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // let the worker enter the row
  auto t0 = std::chrono::steady_clock::now();
  engine.cancel();
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(seconds, 5.0);  // generous (a pixel takes milliseconds): this catches waiting for the row
  EXPECT_TRUE(engine.progress().finished);
  EXPECT_EQ(engine.progress().spp, 0u);
}

TEST(Engine, CancelReachesInsideAPreviewRowOfExpensiveBlocks) {
  // The preview's one block row of 4096 blocks (a sample each) takes tens of seconds, as the row above:
  // a restart during the preview must not wait for it.
  auto job = expensiveRowJob();
  job->settings.camera.width = 4 * 4096;
  Engine engine;
  RenderLimits limits;
  limits.preview = true;
  engine.start(job, limits, 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // let the worker enter the preview
  auto t0 = std::chrono::steady_clock::now();
  engine.cancel();
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(seconds, 5.0);  // generous (a block takes milliseconds): this catches waiting for the row
  EXPECT_TRUE(engine.progress().finished);
  EXPECT_EQ(engine.progress().spp, 0u);
}

TEST(Engine, RequestStopFinishesTheCurrentPass) {
  auto job = smallJob();
  Engine engine;
  engine.start(job, RenderLimits{}, 2);
  ASSERT_TRUE(eventually([&] { return engine.progress().spp > 0; }));
  engine.requestStop();
  engine.wait();
  uint32_t spp = engine.progress().spp;
  EXPECT_GT(spp, 0u);
  // The film holds exactly `spp` whole passes: it equals a fresh render of that many passes.
  Image stopped = engine.film().mean(spp);
  EXPECT_EQ(stopped.rgb, render(job, spp, 1).rgb);
}

TEST(Engine, PausedRenderMakesNoProgress) {
  auto job = smallJob();
  Engine engine;
  engine.start(job, RenderLimits{}, 2);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  engine.setPaused(true);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  uint32_t a = engine.progress().spp;
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_LE(engine.progress().spp, a + 1);  // at most the pass that was running when paused
  uint32_t b = engine.progress().spp;
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(engine.progress().spp, b);
  engine.setPaused(false);
  EXPECT_TRUE(eventually([&] { return engine.progress().spp > b; }));
  engine.cancel();
}

TEST(Engine, SnapshotsArePublishedOnRequest) {
  auto job = smallJob();
  Engine engine;
  engine.start(job, RenderLimits{}, 2);
  FilmSnapshot snap;
  bool got = false;
  for (int i = 0; i < 200 && !got; ++i) {
    engine.requestSnapshot(true);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    got = engine.latestSnapshot(snap) && snap.spp > 0;
  }
  engine.cancel();
  ASSERT_TRUE(got);
  EXPECT_EQ(snap.mean.width, 48);
  EXPECT_EQ(snap.standardError.width, 48);
}

// A one-off request of the next pass is published once, with its standard error, at the end of the
// pass after the running one (not at the next boundary, and no later pass with it), and equals the film.
TEST(Engine, NextPassSnapshotIsPublishedOnceAfterThatPass) {
  auto job = smallJob();
  Engine engine;
  engine.start(job, RenderLimits{100000, 0.0}, 2);
  FilmSnapshot::Probe probe;
  auto resting = [&] { return engine.probeAtRest(0, 0, probe); };  // a worker waits at a boundary
  engine.setPaused(true);
  ASSERT_TRUE(eventually(resting));
  FilmSnapshot before;
  engine.takeSnapshot(before);
  const uint32_t spp = engine.progress().spp;
  engine.requestNextPassSnapshot(true);  // during the pass after this boundary
  engine.setPaused(false);
  ASSERT_TRUE(eventually([&] { return engine.progress().spp >= spp + 6; }));
  engine.setPaused(true);
  ASSERT_TRUE(eventually(resting));
  FilmSnapshot got;
  ASSERT_TRUE(engine.takeSnapshot(got));
  engine.cancel();
  EXPECT_EQ(got.version, before.version + 1) << "not published exactly once";
  EXPECT_EQ(got.spp, spp + 2);
  ASSERT_EQ(got.standardError.width, 48);
  Engine reference;
  reference.start(job, RenderLimits{got.spp, 0.0}, 1);
  reference.wait();
  EXPECT_EQ(got.mean.rgb, reference.film().mean(got.spp).rgb);
  EXPECT_EQ(got.standardError.rgb, reference.film().standardError(got.spp).rgb);
}

TEST(Engine, TimeLimitStopsTheRender) {
  auto job = smallJob();
  Engine engine;
  engine.start(job, RenderLimits{0, 0.05}, 2);
  engine.wait();
  EXPECT_TRUE(engine.progress().finished);
  EXPECT_GE(engine.progress().seconds, 0.05);
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

TEST(Engine, ExtendingTheTargetContinuesTheSameAccumulation) {
  auto job = smallJob();
  Engine engine;
  engine.start(job, RenderLimits{3, 0.0}, 2);
  engine.wait();
  ASSERT_EQ(engine.progress().spp, 3u);
  ASSERT_TRUE(engine.extend(RenderLimits{7, 0.0}));
  engine.wait();
  EXPECT_EQ(engine.progress().spp, 7u);
  // Passes 3..6 continued the same streams: identical to rendering 7 passes at once.
  EXPECT_EQ(engine.film().mean(7).rgb, render(job, 7, 2).rgb);
}

TEST(Engine, PreviewIsPublishedBeforeTheFirstPass) {
  auto job = smallJob();
  Engine engine;
  RenderLimits limits{1, 0.0};
  limits.preview = true;
  engine.requestSnapshot();
  engine.start(job, limits, 2);
  engine.wait();
  FilmSnapshot snap;
  ASSERT_TRUE(engine.latestSnapshot(snap));
  EXPECT_EQ(snap.spp, 1u);  // the final pass is always published, after the preview
  EXPECT_EQ(snap.mean.width, 48);
  EXPECT_EQ(engine.film().mean(1).rgb, render(job, 1, 1).rgb);  // the preview never touches the film
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// A viewer that keeps asking gets every pass resolved row by row during the pass; those snapshots
// equal the film resolved at the same spp (mean and standard error, bit for bit), whether read by
// copy (latestSnapshot) or by swapping buffers with the engine (takeSnapshot).
void expectStreamedSnapshotsEqualTheFilm(bool take) {
  auto job = smallJob();
  Engine engine;
  // Passes of this tiny image take microseconds: enough of them that a poller descheduled on a busy
  // machine still sees some, and the render is cancelled once it has seen a few.
  RenderLimits limits{2000, 0.0};
  limits.preview = true;
  engine.start(job, limits, 2);
  std::vector<FilmSnapshot> seen;
  FilmSnapshot snap;
  while (!engine.progress().finished && seen.size() < 8) {
    engine.requestSnapshot(true);
    bool got = take ? engine.takeSnapshot(snap) : engine.latestSnapshot(snap);
    if (got && snap.spp >= 2 && !snap.standardError.empty()) seen.push_back(snap);
    std::this_thread::yield();
  }
  engine.cancel();
  ASSERT_FALSE(seen.empty());
  Engine reference;
  for (size_t i = 0; i < seen.size(); i += std::max<size_t>(1, seen.size() / 5)) {
    const FilmSnapshot& s = seen[i];
    reference.start(job, RenderLimits{s.spp, 0.0}, 1);
    reference.wait();
    EXPECT_EQ(s.mean.rgb, reference.film().mean(s.spp).rgb) << "spp " << s.spp;
    EXPECT_EQ(s.standardError.rgb, reference.film().standardError(s.spp).rgb) << "spp " << s.spp;
  }
}

TEST(Engine, StreamedSnapshotsEqualTheFilmAtTheirSpp) {
  expectStreamedSnapshotsEqualTheFilm(false);
}

TEST(Engine, TakenSnapshotsEqualTheFilmAtTheirSpp) {
  expectStreamedSnapshotsEqualTheFilm(true);
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// The film sums of the parts of a block schedule, each rendered round by round (one block per
// extend, as processes that share a render do), added together and divided by the passes rendered.
std::vector<double> summedParts(std::shared_ptr<RenderJob> job, uint32_t spp, uint32_t block, uint32_t parts,
                                bool overlapping = false) {
  std::vector<double> total;
  uint64_t totalPasses = 0;
  for (uint32_t r = 0; r < parts; ++r) {
    const SampleSchedule schedule = SampleSchedule::blocks(block, overlapping ? 0 : r, parts);
    const uint32_t passes = uint32_t(schedule.passesBelow(spp));
    if (passes == 0) continue;
    Engine engine;
    engine.start(job, RenderLimits{std::min(block, passes), 0.0}, 2, schedule);
    engine.wait();
    for (uint32_t done = engine.progress().spp; done < passes; done = engine.progress().spp) {
      EXPECT_TRUE(engine.extend(RenderLimits{std::min(done + block, passes), 0.0}));
      engine.wait();
    }
    EXPECT_EQ(engine.progress().spp, passes);
    totalPasses += passes;
    const std::vector<double>& sums = engine.film().sums();
    if (total.empty()) total.assign(sums.size(), 0.0);
    for (size_t i = 0; i < sums.size(); ++i) total[i] += sums[i];
  }
  if (!overlapping) {
    EXPECT_EQ(totalPasses, spp);
  }
  for (double& v : total) v /= double(totalPasses);
  return total;
}

double maxRelativeDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::abs(a[i] - b[i]) / std::max({std::abs(a[i]), std::abs(b[i]), 1e-30}));
  return worst;
}

TEST(Engine, BlockSchedulePartsSumToTheWholeRender) {
  for (const SamplerRow& row : samplerTable()) {  // every sampler, low-discrepancy ones included
    const SamplerKind kind = row.kind;
    auto job = smallJob();
    job->settings.samplerKind = kind;
    Engine whole;
    whole.start(job, RenderLimits{37, 0.0}, 2);  // 37: not a multiple of the block or of the parts
    whole.wait();
    std::vector<double> expected = whole.film().sums();
    for (double& v : expected) v /= 37.0;
    for (uint32_t parts : {1u, 2u, 3u})
      EXPECT_LT(maxRelativeDifference(summedParts(job, 37, 4, parts), expected), 1e-12)
          << samplerKindName(kind) << ", " << parts << " parts";
    // A schedule whose parts overlap (every part from block 0) renders some indices twice and others
    // never: a valid estimate, but not the same one, and the check sees it.
    EXPECT_GT(maxRelativeDifference(summedParts(job, 37, 4, 2, /*overlapping=*/true), expected), 1e-3);
  }
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// The film sums of row y (6 doubles per pixel).
std::vector<double> rowSums(const Film& film, int y) {
  const size_t n = size_t(film.width()) * 6;
  const auto begin = film.sums().begin() + std::ptrdiff_t(size_t(y) * n);
  return std::vector<double>(begin, begin + std::ptrdiff_t(n));
}

// Stops a render of `job` inside a pass (some rows ahead), retrying a few times in case a stop lands on
// a pass boundary; returns false if none landed inside one.
bool stopInsideAPass(Engine& engine, std::shared_ptr<RenderJob> job, SampleSchedule schedule) {
  for (int attempt = 0; attempt < 16; ++attempt) {
    engine.start(job, RenderLimits{}, 3, schedule);
    if (!eventually([&] { return engine.progress().spp >= 2; })) continue;
    // Stopped as soon as the running pass is partway through its rows (spinning: a sleep on a loaded
    // machine can outlast the pass).
    const auto t0 = std::chrono::steady_clock::now();
    for (RenderProgress p = engine.progress();
         !(p.passRows > 0 && p.passRows < p.rows * 3 / 4) &&
         std::chrono::steady_clock::now() - t0 < std::chrono::seconds(2);
         p = engine.progress())
      std::this_thread::yield();
    engine.stopNow();
    engine.wait();
    const std::vector<uint32_t>& rows = engine.rowPasses();
    const uint32_t spp = engine.progress().spp;
    if (std::count(rows.begin(), rows.end(), spp + 1) > 0) return true;
  }
  return false;
}

// Stopped now, every row of the film holds whole passes: rows that completed the interrupted pass equal,
// bit for bit, a render of spp + 1 passes, the others (the ones being rendered, rolled back, and the ones
// not reached) a render of spp passes; rowPasses() says which is which. Both ways of stopping the rows
// being rendered: rolled back from the worker's copy (Always), finished (Never).
void expectStopNowKeepsWholeRows(Engine::RowRollback mode) {
  auto job = smallJob();
  job->settings.camera.width = 64;
  job->settings.camera.height = 96;
  job->settings.integrator.samples = 24;  // passes of a few milliseconds: a stop lands inside one
  const SampleSchedule schedule = SampleSchedule::blocks(4, 1, 2);
  Engine engine;
  engine.setRowRollback(mode);
  ASSERT_TRUE(stopInsideAPass(engine, job, schedule)) << "no stop landed inside a pass";
  const uint32_t spp = engine.progress().spp;
  const std::vector<uint32_t> rows = engine.rowPasses();
  ASSERT_EQ(rows.size(), 96u);
  Engine whole, ahead;
  whole.start(job, RenderLimits{spp, 0.0}, 2, schedule);
  ahead.start(job, RenderLimits{spp + 1, 0.0}, 2, schedule);
  whole.wait();
  ahead.wait();
  int rowsAhead = 0;
  for (int y = 0; y < 96; ++y) {
    ASSERT_TRUE(rows[size_t(y)] == spp || rows[size_t(y)] == spp + 1) << "row " << y;
    const bool isAhead = rows[size_t(y)] == spp + 1;
    rowsAhead += isAhead;
    EXPECT_EQ(rowSums(engine.film(), y), rowSums((isAhead ? ahead : whole).film(), y))
        << "row " << y << " (" << rows[size_t(y)] << " passes)";
  }
  EXPECT_GT(rowsAhead, 0);
  EXPECT_LT(rowsAhead, 96);
  // Resolved with its own count, each row is the mean of its passes.
  Image mean(64, 96);
  engine.film().resolveMean(rows, mean, 0, 96);
  const Image meanWhole = whole.film().mean(spp), meanAhead = ahead.film().mean(spp + 1);
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 64; ++x)
      ASSERT_EQ(mean.at(x, y), (rows[size_t(y)] == spp ? meanWhole : meanAhead).at(x, y));
  // The rows ahead would get the next pass twice: the render cannot be continued.
  EXPECT_FALSE(engine.extend(RenderLimits{spp + 4, 0.0}));
}

TEST(Engine, StopNowKeepsExactlyTheRowsThatCompletedThePass) {
  expectStopNowKeepsWholeRows(Engine::RowRollback::Always);
}

TEST(Engine, StopNowWithoutRollbackFinishesTheRowsBeingRendered) {
  expectStopNowKeepsWholeRows(Engine::RowRollback::Never);
}

// A row of expensive pixels (tens of seconds) is abandoned within a pixel and rolled back: Auto copies
// rows in the first pass and in passes after slow rows.
TEST(Engine, StopNowAbandonsAnExpensiveRowAndRollsItBack) {
  auto job = expensiveRowJob();
  Engine engine;
  engine.start(job, RenderLimits{}, 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // let the worker enter the row
  const auto t0 = std::chrono::steady_clock::now();
  engine.stopNow();
  engine.wait();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(seconds, 5.0);  // generous (a pixel takes milliseconds): this catches finishing the row
  EXPECT_EQ(engine.progress().spp, 0u);
  EXPECT_EQ(engine.rowPasses(), std::vector<uint32_t>(1, 0u));
  EXPECT_EQ(engine.film().sums(), std::vector<double>(4096 * 6, 0.0));  // the partial row was undone
}

TEST(Engine, StopNowAtRestKeepsEveryRowAtTheSamePasses) {
  auto job = smallJob();
  Engine engine;
  engine.start(job, RenderLimits{5, 0.0}, 2);
  engine.wait();
  engine.stopNow();  // after the render: nothing changes
  EXPECT_EQ(engine.progress().spp, 5u);
  EXPECT_EQ(engine.rowPasses(), std::vector<uint32_t>(32, 5u));
  ASSERT_TRUE(engine.extend(RenderLimits{7, 0.0}));
  engine.wait();
  EXPECT_EQ(engine.rowPasses(), std::vector<uint32_t>(32, 7u));
  EXPECT_EQ(engine.film().sums(), [&] {
    Engine fresh;
    fresh.start(job, RenderLimits{7, 0.0}, 1);
    fresh.wait();
    return fresh.film().sums();
  }());
}

// ---- a worker that throws: the render ends, the calling thread gets the exception ----------------

// The scene's rows, except that row `failRow` of pass `failPass` throws std::bad_alloc (as resolving a
// snapshot does when memory runs out).
std::function<RowRenderer(const RenderJob&)> failingRows(int failRow, uint32_t failPass) {
  return [=](const RenderJob& job) {
    RowRenderer rows = makeRowRenderer(job);
    auto row = rows.row;
    rows.row = [=](int y, uint32_t pass, Sampler& sampler, Film& film, uint64_t& bad,
                   const std::atomic<bool>& cancel) {
      if (y == failRow && pass == failPass) throw std::bad_alloc();
      row(y, pass, sampler, film, bad, cancel);
    };
    return rows;
  };
}

TEST(Engine, AWorkerThatThrowsEndsTheRenderAndWaitRethrowsOnTheCallingThread) {
  for (int threads : {1, 2, 4}) {
    Engine engine;
    engine.setRowRendererFactory(failingRows(5, 2));
    engine.start(smallJob(), RenderLimits{}, threads);  // unlimited: only the failure ends it
    ASSERT_TRUE(eventually([&] { return engine.progress().finished; })) << threads << " threads";
    EXPECT_THROW(engine.wait(), std::bad_alloc);
    EXPECT_TRUE(engine.failure() != nullptr);
    EXPECT_EQ(engine.progress().spp, 2u);  // passes 0 and 1 completed, pass 2 failed
    // The next render starts clean.
    engine.setRowRendererFactory(nullptr);
    engine.start(smallJob(), RenderLimits{3, 0.0}, threads);
    EXPECT_NO_THROW(engine.wait());
    EXPECT_EQ(engine.failure(), nullptr);
    EXPECT_EQ(engine.progress().spp, 3u);
  }
}

TEST(Engine, AWorkerThatFailsToStartDoesNotHoldUpTheOthers) {
  Engine engine;
  std::atomic<int> made{0};
  engine.setRowRendererFactory([&](const RenderJob& job) {
    if (made++ == 1) throw Error("the second worker's row renderer");
    return makeRowRenderer(job);
  });
  engine.start(smallJob(), RenderLimits{}, 3);
  ASSERT_TRUE(eventually([&] { return engine.progress().finished; }));
  EXPECT_THROW(engine.wait(), Error);
}

TEST(Engine, AFailureDuringThePreviewEndsTheRender) {
  Engine engine;
  engine.setRowRendererFactory([](const RenderJob& job) {
    RowRenderer rows = makeRowRenderer(job);
    rows.preview = [](int, int, Sampler&, Image&, const std::atomic<bool>&) { throw std::bad_alloc(); };
    return rows;
  });
  RenderLimits limits;
  limits.preview = true;
  engine.start(smallJob(), limits, 2);
  ASSERT_TRUE(eventually([&] { return engine.progress().finished; }));
  EXPECT_THROW(engine.wait(), std::bad_alloc);
  EXPECT_EQ(engine.progress().spp, 0u);
}

}  // namespace
}  // namespace penumbra
