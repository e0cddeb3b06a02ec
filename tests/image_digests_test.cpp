// Images stay byte-identical: every strategy of every scene under scenes/, with every sampler,
// rendered small (24x18, 4 spp, seed 1) and digested, against tests/image_digests.txt.
//
// The file is the contract, not the code: each line names the scene and the `--set` overrides that
// select the strategy and sampler in the scenes' own XML spellings, so the check survives any
// restructuring of how strategies are represented, and a line that no longer renders, or renders
// differently, fails. Scenes traced by Embree render bit for bit alike only on machines whose Embree
// kernels use one instruction set (embreeKernelIsa): their lines carry a fourth column naming it
// ("embree-avx512"), a machine compares the lines of its own, and recording keeps the other sets'
// lines. Recording (from a build whose images are right):
//   PENUMBRA_RECORD_IMAGE_DIGESTS=tests/image_digests.txt build/penumbra_tests
//   --gtest_filter='ImageDigests.*'
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "core/geometry/scene_geometry.h"
#include "core/math/error.h"
#include "core/render/engine.h"
#include "core/render/strategy_axes.h"
#include "core/sampling/sampler_table.h"
#include "core/scene/scene_builder.h"
#include "tests/test_support.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using Overrides = std::vector<std::pair<std::string, std::string>>;

constexpr uint32_t kSpp = 4;
const Overrides kSmall = {{"camera.width", "24"}, {"camera.height", "18"}};

// The scenes too heavy to load thousands of times as they are, and what keeps them light.
const std::map<std::string, Overrides> kSceneOverrides = {
    {"standin/rock-ao.xml", {{"shape.subdivisions", "4"}}},
};

std::string digestsFile() {
  return test::sourcePath("tests/image_digests.txt");
}

// FNV-1a over the bits of every channel of every pixel of the mean image.
uint64_t digest(const Image& image) {
  uint64_t h = 1469598103934665603ull;
  for (float v : image.rgb) {
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int i = 0; i < 4; ++i) h = (h ^ ((bits >> (8 * i)) & 0xffu)) * 1099511628211ull;
  }
  return h;
}

Overrides sceneOverrides(const std::string& scene, const Overrides& selection) {
  Overrides all = kSmall;
  if (auto it = kSceneOverrides.find(scene); it != kSceneOverrides.end())
    all.insert(all.end(), it->second.begin(), it->second.end());
  all.insert(all.end(), selection.begin(), selection.end());
  return all;
}

// Renders as `penumbra render --spp 4 --seed 1` does.
std::string renderDigest(const LoadedScene& s) {
  RenderSettings settings = s.settings;
  settings.seed = 1;
  const RenderLimits limits{kSpp, 0.0};
  Engine engine;
  engine.start(std::make_shared<const RenderJob>(s.scene, settings, limits), limits);
  engine.wait();
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", (unsigned long long)digest(engine.film().mean(kSpp)));
  return text;
}

std::string joinSelection(const Overrides& selection) {
  std::string out;
  for (const auto& [key, value] : selection) out += (out.empty() ? "" : " ") + key + "=" + value;
  return out;
}

Overrides splitSelection(const std::string& text) {
  Overrides out;
  std::istringstream in(text);
  for (std::string word; in >> word;) {
    size_t eq = word.find('=');
    if (eq == std::string::npos) throw Error("image_digests.txt: '" + word + "' is not KEY=VALUE");
    out.emplace_back(word.substr(0, eq), word.substr(eq + 1));
  }
  return out;
}

struct DigestLine {
  std::string scene, selection, digest;
  std::string kernels;  // "embree-ISA" for a scene traced by Embree, else empty
};

// The kernels whose rounding a scene's image depends on beyond the renderer's own.
std::string kernelsOf(const LoadedScene& s) {
  const SceneGeometry& g = s.scene->geometry;
  return g.usesEmbree() || g.spheresUseBvh() ? "embree-" + embreeKernelIsa() : "";
}

std::vector<std::string> sceneFiles() {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(test::sourcePath("scenes")))
    if (e.is_regular_file() && e.path().extension() == ".xml")
      out.push_back(fs::relative(e.path(), test::sourcePath("scenes")).string());
  std::sort(out.begin(), out.end());
  return out;
}

// The name under which the scene's <integrator> already gives the property `canonical` (an override
// in another spelling would be a second spelling of one setting); `canonical` when it gives none.
std::string sceneSpelling(const SceneNode& integrator, std::string_view canonical) {
  for (const Spellings* p : {&kMeasureProperty, &kWarpProperty, &kLightSelectionProperty,
                             &kLightMeasureProperty, &kHeuristicProperty})
    if (p->canonical() == canonical)
      if (const Property* given = integrator.props.find(p->list())) return given->name;
  return std::string(canonical);
}

// A strategy x sampler of a scene, selected through the XML properties (the scene's shading samples
// and counts stay as the scene gives them).
struct Selection {
  IntegratorDesc strategy;
  SamplerKind sampler;
  Overrides overrides;
};

// Every strategy of the scene's integrator type x every sampler; none for a scene that must not load
// (the stiff cases whose own tests say so).
std::vector<Selection> selectionsOf(const std::string& scene) {
  std::vector<Selection> out;
  LoadedScene base;
  try {
    base = loadScene(test::sourcePath("scenes/" + scene), sceneOverrides(scene, {}));
  } catch (const Error&) {
    return out;
  }
  const SceneNode* integrator = base.desc.child("integrator");
  for (const IntegratorDesc& desc : everyStrategyOfType(base.settings.integrator)) {
    Overrides strategySelection;
    for (const CanonicalProperty& p : canonicalProperties(desc))
      if (!p.isInteger)
        strategySelection.emplace_back(
            "integrator." + (integrator ? sceneSpelling(*integrator, p.name) : std::string(p.name)), p.value);
    for (const SamplerRow& sampler : samplerTable()) {
      Overrides selection = strategySelection;
      selection.emplace_back("sampler.type", samplerKindName(sampler.kind));
      out.push_back({desc, sampler.kind, selection});
    }
  }
  return out;
}

std::vector<DigestLine> recordScene(const std::string& scene) {
  std::vector<DigestLine> out;
  for (const Selection& sel : selectionsOf(scene)) {
    LoadedScene s = loadScene(test::sourcePath("scenes/" + scene), sceneOverrides(scene, sel.overrides));
    const std::string text = joinSelection(sel.overrides);
    EXPECT_EQ(strategyLabel(s.settings.integrator), strategyLabel(sel.strategy)) << scene << " " << text;
    EXPECT_EQ(s.settings.samplerKind, sel.sampler) << scene << " " << text;
    out.push_back({scene, text, renderDigest(s), kernelsOf(s)});
  }
  return out;
}

std::vector<DigestLine> readDigests() {
  std::ifstream in(digestsFile());
  if (!in) throw Error(digestsFile() + ": cannot read");
  std::vector<DigestLine> out;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    for (size_t start = 0;;) {
      const size_t tab = line.find('\t', start);
      fields.push_back(line.substr(start, tab == std::string::npos ? std::string::npos : tab - start));
      if (tab == std::string::npos) break;
      start = tab + 1;
    }
    if (fields.size() != 3 && fields.size() != 4)
      throw Error("image_digests.txt: not SCENE<tab>SETS<tab>DIGEST[<tab>KERNELS]: " + line);
    fields.resize(4);
    out.push_back({fields[0], fields[1], fields[2], fields[3]});
  }
  return out;
}

TEST(ImageDigests, EveryStrategyAndSamplerRendersTheRecordedImage) {
  const std::string here = "embree-" + embreeKernelIsa();
  if (const char* record = std::getenv("PENUMBRA_RECORD_IMAGE_DIGESTS")) {
    // Other instruction sets' Embree lines are kept (this machine cannot render them).
    std::vector<DigestLine> kept;
    for (const DigestLine& d : readDigests())
      if (!d.kernels.empty() && d.kernels != here) kept.push_back(d);
    std::vector<DigestLine> lines;
    for (const std::string& scene : sceneFiles())
      for (const DigestLine& d : recordScene(scene)) lines.push_back(d);
    const size_t n = lines.size();
    lines.insert(lines.end(), kept.begin(), kept.end());
    std::stable_sort(lines.begin(), lines.end(), [](const DigestLine& a, const DigestLine& b) {
      return std::tie(a.scene, a.kernels) < std::tie(b.scene, b.kernels);
    });
    std::ofstream out(record);
    out << "# scene\t--set overrides (besides camera.width=24 camera.height=18)\tFNV-1a of the mean image "
           "(4 spp, seed 1)\t[the Embree kernels' instruction set, for scenes traced by Embree]\n";
    for (const DigestLine& d : lines)
      out << d.scene << '\t' << d.selection << '\t' << d.digest << (d.kernels.empty() ? "" : "\t" + d.kernels)
          << '\n';
    std::printf("recorded %zu digests in %s (%zu kept of other Embree kernels)\n", n, record, kept.size());
    return;
  }
  const std::vector<DigestLine> lines = readDigests();
  ASSERT_GT(lines.size(), 1000u);
  // Lines of scenes traced by Embree with no line for this machine's kernels are not compared.
  std::set<std::pair<std::string, std::string>> ofHere, ofOthers;
  for (const DigestLine& d : lines)
    if (!d.kernels.empty()) (d.kernels == here ? ofHere : ofOthers).insert({d.scene, d.selection});
  size_t uncompared = 0;
  for (const auto& key : ofOthers) uncompared += !ofHere.count(key);
  if (uncompared > 0)
    std::printf("%zu images traced by Embree have no digest recorded for its %s kernels here: not compared\n",
                uncompared, embreeKernelIsa().c_str());
  size_t differing = 0, compared = 0;
  for (const DigestLine& d : lines) {
    if (!d.kernels.empty() && d.kernels != here) continue;
    LoadedScene s;
    try {
      s = loadScene(test::sourcePath("scenes/" + d.scene),
                    sceneOverrides(d.scene, splitSelection(d.selection)));
    } catch (const Error& e) {
      ADD_FAILURE() << d.scene << " " << d.selection << ": no longer loads: " << e.what();
      continue;
    }
    ++compared;
    if (kernelsOf(s) != d.kernels) {
      ADD_FAILURE() << d.scene << " " << d.selection << ": recorded as traced by '" << d.kernels
                    << "', traced by '" << kernelsOf(s) << "' now";
      continue;
    }
    const std::string now = renderDigest(s);
    if (now != d.digest && ++differing <= 20)
      ADD_FAILURE() << d.scene << " " << d.selection << ": digest " << now << ", recorded " << d.digest;
  }
  EXPECT_EQ(differing, 0u) << "of " << compared << " images";
  EXPECT_GT(compared, 1000u);
}

// A strategy or scene added since the file was recorded has no digest to keep: the file must be
// re-recorded (the command at the top), which also shows that the old lines did not change.
TEST(ImageDigests, EveryStrategyAndSamplerOfEverySceneIsRecorded) {
  std::set<std::pair<std::string, std::string>> recorded;
  for (const DigestLine& d : readDigests()) recorded.insert({d.scene, d.selection});
  size_t missing = 0;
  for (const std::string& scene : sceneFiles())
    for (const Selection& sel : selectionsOf(scene))
      if (!recorded.count({scene, joinSelection(sel.overrides)}) && ++missing <= 10)
        ADD_FAILURE() << scene << " " << joinSelection(sel.overrides) << ": no recorded digest";
  EXPECT_EQ(missing, 0u) << "re-record tests/image_digests.txt (see the top of this file)";
}

}  // namespace
}  // namespace penumbra
