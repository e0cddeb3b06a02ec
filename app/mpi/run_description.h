// What a rank of `penumbra-mpi render` is about to render, as (name, canonical value) pairs: the
// settings that decide the image (size, spp, block, seed, sampler, integrator, limits, output mode)
// and the whole resolved scene (every object and property after --set, and the bytes of every file
// the scene names). The ranks compare its digest before rendering: ranks that render different
// things would add up an image that is none of them. No MPI here (the unit tests use it without).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/render/render_settings.h"
#include "core/scene/scene_desc.h"

namespace penumbra::mpi {

struct RunSetting {
  std::string name;   // "camera.width", "block", or a scene entry such as "emitter.radiance"
  std::string value;  // canonical text: equal values are equal strings
  std::string where;  // for messages only, not compared: the scene file and line of a scene entry
  bool inScene = false;
};
using RunDescription = std::vector<RunSetting>;

// The run-level choices that are not part of the resolved settings.
struct RunChoices {
  uint64_t targetSpp = 0;  // 0: until the time limit
  double seconds = 0;      // --time; 0: none
  uint32_t block = 0;      // --block
  bool reference = false;  // --reference
  std::string outputFormat;
};

// Settings first (in the order a user thinks of them), then the scene's entries in document order.
// Paths of the scene and its files are left out (ranks may see the same files under different
// paths); their contents are in. Threads per rank are left out: they do not change the image.
RunDescription describeRun(const RenderSettings& settings, const RunChoices& choices, const SceneNode& scene);

// 64-bit FNV-1a over every name and value (not `where`), in order.
uint64_t digestOf(const RunDescription& description);

// A byte string holding the whole description (names, values, places), and back.
std::string serialize(const RunDescription& description);
RunDescription deserialize(const std::string& bytes);

// How `mine` differs from `root`'s, as the rest of "rank r disagrees with rank 0...": the first
// differing entry in root's order, mine first, e.g. " on camera.width: 64 vs 128" or ": the resolved
// scene differs at emitter.radiance (--set): 1,1,1 vs 300,300,300"; "" when no entry differs.
std::string firstDifference(const RunDescription& mine, const RunDescription& root);

}  // namespace penumbra::mpi
