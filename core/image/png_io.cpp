// PNG through libpng's simplified API (png_image), which keeps libpng's setjmp error handling inside
// the library. Output is 8-bit sRGB from toSrgb8; input of any PNG flavour is converted by libpng to
// 8-bit sRGB RGB and then decoded to linear with the exact piecewise sRGB curve.
#include <png.h>

#include <cstring>
#include <vector>

#include "core/image/atomic_file.h"
#include "core/image/image_io.h"
#include "core/image/tonemap.h"
#include "core/math/bounded_read.h"
#include "core/math/error.h"

namespace penumbra {

void writePng(const std::string& path, const Image& image, const ImageMetadata& /*metadata*/,
              float exposureStops) {
  if (image.width <= 0 || image.height <= 0 || image.rgb.size() != image.pixelCount() * 3)
    throw Error(path, 0, "cannot write an empty or inconsistent image");
  std::vector<std::uint8_t> pixels = toSrgb8(image, exposureStops);

  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;
  if (!png_image_write_get_memory_size(png, size, 0, pixels.data(), 0, nullptr))
    throw Error(path, 0, std::string("cannot encode PNG: ") + png.message);
  std::vector<std::uint8_t> encoded(size);
  if (!png_image_write_to_memory(&png, encoded.data(), &size, 0, pixels.data(), 0, nullptr))
    throw Error(path, 0, std::string("cannot encode PNG: ") + png.message);
  png_image_free(&png);
  writeBytesAtomically(path, encoded.data(), size);
}

Image readPng(const std::string& path) {
  checkNoNulInPath(path, "PNG file");
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw Error(path, 0, std::string("cannot read PNG: ") + png.message);
  png.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, pixels.data(), 0, nullptr)) {
    std::string msg = png.message;
    png_image_free(&png);
    throw Error(path, 0, "cannot read PNG: " + msg);
  }
  Image image(static_cast<int>(png.width), static_cast<int>(png.height));
  png_image_free(&png);
  float table[256];
  for (int k = 0; k < 256; ++k) table[k] = srgbToLinear(static_cast<float>(k) / 255.f);
  for (std::size_t i = 0; i < pixels.size() && i < image.rgb.size(); ++i) image.rgb[i] = table[pixels[i]];
  return image;
}

}  // namespace penumbra
