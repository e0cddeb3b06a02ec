// References: the closed form of the analytic scene against a rendered one, the content hash that
// names cached references, and the cache round trip with the emitter mask.
#include "core/analysis/reference.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "core/analysis/analysis_test_support.h"
#include "core/image/image_io.h"
#include "core/math/error.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

using test::analyticScene;
using test::loadSmall;
using test::sphereScene;

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

TEST(Reference, MissingCacheDirectoryIsCreatedSoTheRenderIsKept) {
  fs::path dir = fs::temp_directory_path() / ("penumbra-ref-new-" + std::to_string(::getpid())) / "a" / "b";
  fs::remove_all(dir.parent_path().parent_path());
  LoadedScene scene = loadSmall(sphereScene(), 8);
  ReferenceRequest rq;
  rq.cacheDir = dir.string();
  rq.referenceSpp = 4;
  obtainReference(scene, rq);
  EXPECT_TRUE(fs::exists(referenceCachePath(scene, dir.string())));
  fs::remove_all(dir.parent_path().parent_path());
}

// What a reference must hold, in memory and in a file: a finite mean (negative values allowed: a
// mitchell filter makes them), a finite non-negative standard error; the count and the first bad value.
std::string referenceProblem(const Reference& ref) {
  try {
    checkReferenceValues(ref, "reference r.exr");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Reference, NonFiniteValuesAreRefusedWithTheFirstPixel) {
  Reference ref{Image(4, 3), Image(4, 3), "test"};
  EXPECT_EQ(referenceProblem(ref), "");
  ref.mean.rgb[ref.mean.index(1, 0) + 2] = -0.25f;  // a negative lobe's value: allowed
  EXPECT_EQ(referenceProblem(ref), "");
  ref.mean.rgb[ref.mean.index(3, 1) + 1] = std::numeric_limits<float>::infinity();
  ref.mean.rgb[ref.mean.index(0, 2) + 0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(referenceProblem(ref),
            "reference r.exr: 2 of 36 values are not finite; the first at pixel (3, 1) channel G: inf");
  ref.mean = Image(4, 3);
  ref.standardError.rgb[ref.standardError.index(2, 2) + 2] = -1e-3f;
  EXPECT_EQ(referenceProblem(ref),
            "reference r.exr (standard error): 1 of 36 values is not finite and non-negative; the first at "
            "pixel (2, 2) channel B: -0.001");
}

TEST(Reference, FilesWithNonFiniteValuesAreRefusedAsTheyAreRead) {
  const fs::path dir = fs::temp_directory_path() / ("penumbra-ref-values-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "nan.pfm").string();
  Image mean(5, 2);
  mean.rgb[mean.index(4, 1)] = std::numeric_limits<float>::quiet_NaN();
  writeImage(path, mean);
  try {
    readReference(path);
    ADD_FAILURE() << "accepted a NaN reference";
  } catch (const Error& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "reference " + path + ": 1 of 30 values is not finite; the first at pixel (4, 1) channel R: nan");
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace penumbra
