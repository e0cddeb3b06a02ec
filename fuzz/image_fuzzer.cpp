// libFuzzer target: the PFM and EXR readers that `penumbra converge` uses for references. The first
// byte picks the format; the rest is the file.
#include <cstdint>

#include "core/image/image_io.h"
#include "core/math/error.h"
#include "fuzz/fuzz_input_file.h"

namespace {

// OpenEXR reports corrupt files with its own exception types (Iex::BaseExc derives from
// std::exception); the reader must turn every one into an Error or an exception, never a crash.
template <class Read>
void readQuietly(Read read) {
  try {
    read();
  } catch (const std::exception&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1 || size > (1 << 20)) return 0;
  static const penumbra::fuzz::ScratchFile pfm(".pfm"), exr(".exr");
  const bool isExr = data[0] & 1;
  const penumbra::fuzz::ScratchFile& file = isExr ? exr : pfm;
  if (!file.write(data + 1, size - 1)) return 0;
  if (isExr) {
    readQuietly([&] { penumbra::readExr(file.path()); });
    readQuietly([&] { penumbra::readExrMetadata(file.path()); });
  } else {
    readQuietly([&] { penumbra::readPfm(file.path()); });
  }
  return 0;
}
