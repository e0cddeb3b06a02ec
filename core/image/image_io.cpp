#include "core/image/image_io.h"

#include <algorithm>
#include <cctype>

#include "core/math/error.h"

namespace penumbra {

namespace {

std::string lowerExtension(const std::string& path) {
  auto slash = path.find_last_of('/');
  auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void checkImage(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0)
    throw Error(path, 0,
                "cannot write an empty image (" + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + ")");
  if (image.rgb.size() != image.pixelCount() * 3)
    throw Error(path, 0,
                "image buffer holds " + std::to_string(image.rgb.size()) + " floats, expected " +
                    std::to_string(image.pixelCount() * 3));
}

}  // namespace

ImageFormat imageFormatFromPath(const std::string& path) {
  std::string ext = lowerExtension(path);
  if (ext == ".exr") return ImageFormat::Exr;
  if (ext == ".pfm") return ImageFormat::Pfm;
  if (ext == ".png") return ImageFormat::Png;
  throw Error(path, 0, "unsupported image extension '" + ext + "' (supported: .exr, .pfm, .png)");
}

void writeImage(const std::string& path, const Image& image, const ImageMetadata& metadata,
                float exposureStops) {
  ImageFormat format = imageFormatFromPath(path);
  checkImage(path, image);
  switch (format) {
    case ImageFormat::Exr:
      writeExr(path, image, metadata);
      return;
    case ImageFormat::Pfm:
      writePfm(path, image);
      return;
    case ImageFormat::Png:
      writePng(path, image, metadata, exposureStops);
      return;
  }
}

Image readImage(const std::string& path) {
  switch (imageFormatFromPath(path)) {
    case ImageFormat::Exr:
      return readExr(path);
    case ImageFormat::Pfm:
      return readPfm(path);
    case ImageFormat::Png:
      return readPng(path);
  }
  throw Error(path, 0, "unreachable");
}

ImageMetadata readImageMetadata(const std::string& path) {
  switch (imageFormatFromPath(path)) {
    case ImageFormat::Exr:
      return readExrMetadata(path);
    case ImageFormat::Pfm:
      readPfm(path);
      break;  // validates; PFM carries no metadata
    case ImageFormat::Png:
      readPng(path);
      break;  // validates; PNG metadata is not stored
  }
  return {};
}

}  // namespace penumbra
