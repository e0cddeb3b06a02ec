// OpenEXR reading/writing through the C++ API (Imf::OutputFile / InputFile with FLOAT slices:
// RgbaOutputFile would be half-only).
#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <half.h>

#include <exception>
#include <vector>

#include "core/image/atomic_file.h"
#include "core/image/image_io.h"
#include "core/math/bounded_read.h"
#include "core/math/error.h"

namespace penumbra {

namespace {

ImageMetadata stringAttributes(const Imf::Header& header) {
  ImageMetadata meta;
  for (auto it = header.begin(); it != header.end(); ++it) {
    if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
      meta.add(it.name(), s->value());
  }
  return meta;
}

}  // namespace

void writeExr(const std::string& path, const Image& image, const ImageMetadata& metadata,
              ExrPixelType pixelType) {
  if (image.width <= 0 || image.height <= 0 || image.rgb.size() != image.pixelCount() * 3)
    throw Error(path, 0, "cannot write an empty or inconsistent image");
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  const Imf::PixelType fileType = pixelType == ExrPixelType::Half ? Imf::HALF : Imf::FLOAT;
  header.channels().insert("R", Imf::Channel(fileType));
  header.channels().insert("G", Imf::Channel(fileType));
  header.channels().insert("B", Imf::Channel(fileType));
  for (const auto& [key, value] : metadata.entries) {
    if (key.empty()) throw Error(path, 0, "EXR metadata key must not be empty");
    if (header.find(key) != header.end())
      throw Error(path, 0, "EXR metadata key '" + key + "' clashes with a standard header attribute");
    header.insert(key, Imf::StringAttribute(value));
  }

  // The frame buffer must have the file's pixel type (OpenEXR converts on input only).
  std::vector<half> halves;
  char* base;
  std::size_t elem;
  if (pixelType == ExrPixelType::Half) {
    halves.assign(image.rgb.begin(), image.rgb.end());
    base = reinterpret_cast<char*>(halves.data());
    elem = sizeof(half);
  } else {
    // OpenEXR only reads from the frame buffer; the const_cast is for its char* slice API.
    base = reinterpret_cast<char*>(const_cast<float*>(image.rgb.data()));
    elem = sizeof(float);
  }
  const std::size_t xStride = 3 * elem, yStride = xStride * static_cast<std::size_t>(image.width);
  Imf::FrameBuffer fb;
  fb.insert("R", Imf::Slice(fileType, base + 0 * elem, xStride, yStride));
  fb.insert("G", Imf::Slice(fileType, base + 1 * elem, xStride, yStride));
  fb.insert("B", Imf::Slice(fileType, base + 2 * elem, xStride, yStride));

  writeFileAtomically(path, [&](const std::string& temp) {
    try {
      Imf::OutputFile file(temp.c_str(), header);
      file.setFrameBuffer(fb);
      file.writePixels(image.height);
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      throw Error(path, 0, std::string("cannot write EXR: ") + e.what());
    }
  });
}

Image readExr(const std::string& path, ImageMetadata* metadata) {
  checkRegularFile(path, kMaxImageFileBytes, "EXR file");
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i dw = header.dataWindow();
    // In 64 bits: a corrupt window's max - min overflows int.
    const int64_t w64 = int64_t(dw.max.x) - dw.min.x + 1, h64 = int64_t(dw.max.y) - dw.min.y + 1;
    if (w64 <= 0 || h64 <= 0) throw Error(path, 0, "EXR has an empty data window");
    if (w64 * h64 > kMaxReadPixels)
      throw Error(path, 0,
                  "EXR data window " + std::to_string(w64) + "x" + std::to_string(h64) + " is larger than " +
                      std::to_string(kMaxReadPixels) + " pixels");
    const int width = int(w64), height = int(h64);

    const Imf::ChannelList& channels = header.channels();
    const bool hasR = channels.findChannel("R"), hasG = channels.findChannel("G"),
               hasB = channels.findChannel("B"), hasY = channels.findChannel("Y");
    const bool rgb = hasR || hasG || hasB;
    if (!rgb && !hasY) {
      std::string names;
      for (auto it = channels.begin(); it != channels.end(); ++it) names += std::string(" ") + it.name();
      throw Error(path, 0, "EXR has no R/G/B or Y channel (channels:" + names + ")");
    }
    if (channels.findChannel("RY") || channels.findChannel("BY"))
      throw Error(path, 0, "luminance/chroma (RY/BY) EXR files are not supported");

    Image image(width, height);
    const std::size_t xStride = 3 * sizeof(float), yStride = xStride * static_cast<std::size_t>(width);
    // Slices are addressed by absolute data-window coordinates.
    char* base = reinterpret_cast<char*>(image.rgb.data()) - static_cast<std::ptrdiff_t>(dw.min.x) * xStride -
                 static_cast<std::ptrdiff_t>(dw.min.y) * yStride;
    Imf::FrameBuffer fb;
    if (rgb) {
      // Missing colour channels are filled with 0.
      fb.insert("R", Imf::Slice(Imf::FLOAT, base + 0 * sizeof(float), xStride, yStride, 1, 1, 0.0));
      fb.insert("G", Imf::Slice(Imf::FLOAT, base + 1 * sizeof(float), xStride, yStride, 1, 1, 0.0));
      fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xStride, yStride, 1, 1, 0.0));
    } else {
      fb.insert("Y", Imf::Slice(Imf::FLOAT, base, xStride, yStride, 1, 1, 0.0));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    if (!rgb)
      for (std::size_t i = 0; i < image.rgb.size(); i += 3)
        image.rgb[i + 1] = image.rgb[i + 2] = image.rgb[i];
    if (metadata) *metadata = stringAttributes(header);
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(path, 0, std::string("cannot read EXR: ") + e.what());
  }
}

ImageMetadata readExrMetadata(const std::string& path) {
  checkRegularFile(path, kMaxImageFileBytes, "EXR file");
  try {
    Imf::InputFile file(path.c_str());
    return stringAttributes(file.header());
  } catch (const std::exception& e) {
    throw Error(path, 0, std::string("cannot read EXR: ") + e.what());
  }
}

}  // namespace penumbra
