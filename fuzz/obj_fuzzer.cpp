// libFuzzer target: the OBJ loader (our line-numbered pre-scan, then tinyobjloader, then the mesh).
#include <cstdint>

#include <glm/mat4x4.hpp>

#include "core/math/error.h"
#include "core/scene/obj_loader.h"
#include "fuzz/fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > (1 << 16)) return 0;
  static const penumbra::fuzz::ScratchFile file(".obj");
  if (!file.write(data, size)) return 0;
  try {
    penumbra::loadObjMesh(file.path(), glm::mat4(1.f), "fuzz.xml", 1);
  } catch (const penumbra::Error&) {
  }
  return 0;
}
