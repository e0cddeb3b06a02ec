// libFuzzer target: scene XML through the parser and the builder (geometry, lights, settings), as
// `penumbra render` loads it. Relative mesh paths resolve against PENUMBRA_FUZZ_SCENE_DIR, so seed
// scenes that name plane.obj or sphere.obj load their meshes.
#include <cstdint>
#include <string>

#include "core/math/error.h"
#include "core/scene/scene_builder.h"
#include "core/scene/xml_parser.h"

namespace {

// Procedural rocks above this many subdivisions (4^n * 20 triangles) take seconds to build under
// ASan; they exercise no parsing the smaller ones do not.
bool affordable(const penumbra::SceneNode& node) {
  if (node.type == "rock") {
    const penumbra::Property* p = node.props.find({"subdivisions"});
    if (!p || p->intValue > 5) return false;
  }
  for (const penumbra::SceneNode& c : node.children)
    if (!affordable(c)) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > (1 << 16)) return 0;
  const std::string xml(reinterpret_cast<const char*>(data), size);
  try {
    penumbra::SceneNode desc = penumbra::parseSceneString(xml, "fuzz.xml", PENUMBRA_FUZZ_SCENE_DIR);
    if (!affordable(desc)) return 0;
    penumbra::LoadedScene loaded = penumbra::buildScene(std::move(desc));
    (void)penumbra::writeSceneXml(loaded.desc);
  } catch (const penumbra::Error&) {
    // Rejected with a message: the expected outcome for most inputs.
  }
  return 0;
}
