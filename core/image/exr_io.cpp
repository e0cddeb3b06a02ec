// OpenEXR reading/writing through the C++ API (Imf::OutputFile / InputFile with FLOAT slices:
// RgbaOutputFile would be half-only).
#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>
#include <half.h>
#include <openexr.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <thread>
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

// OpenEXR compresses and decompresses line blocks on its own thread pool, none by default: on all
// cores a 768² image is written in about half the time.
void useEveryCoreForExr() {
  static const bool once = [] {
    Imf::setGlobalThreadCount(int(std::max(1u, std::thread::hardware_concurrency())));
    return true;
  }();
  (void)once;
}

}  // namespace

void writeExr(const std::string& path, const Image& image, const ImageMetadata& metadata,
              ExrPixelType pixelType, ExrCompression compression) {
  useEveryCoreForExr();
  if (image.width <= 0 || image.height <= 0 || image.rgb.size() != image.pixelCount() * 3)
    throw Error(path, 0, "cannot write an empty or inconsistent image");
  Imf::Header header(image.width, image.height);
  header.compression() = compression == ExrCompression::None ? Imf::NO_COMPRESSION : Imf::ZIP_COMPRESSION;
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

namespace {

// Bytes OpenEXR 3.1 reads for a value of each fixed-size attribute type; 0: variable or unknown
// (string, vectors, opaque types are read by their declared size; chlist and preview are walked).
int fixedAttributeSize(const std::string& type) {
  static const std::pair<const char*, int> kSizes[] = {{"box2i", 16},
                                                       {"box2f", 16},
                                                       {"chromaticities", 32},
                                                       {"compression", 1},
                                                       {"deepImageState", 1},
                                                       {"double", 8},
                                                       {"envmap", 1},
                                                       {"float", 4},
                                                       {"int", 4},
                                                       {"keycode", 28},
                                                       {"lineOrder", 1},
                                                       {"m33f", 36},
                                                       {"m33d", 72},
                                                       {"m44f", 64},
                                                       {"m44d", 128},
                                                       {"rational", 8},
                                                       {"tiledesc", 9},
                                                       {"timecode", 8},
                                                       {"v2i", 8},
                                                       {"v2f", 8},
                                                       {"v2d", 16},
                                                       {"v3i", 12},
                                                       {"v3f", 12},
                                                       {"v3d", 24}};
  for (const auto& [name, size] : kSizes)
    if (type == name) return size;
  return 0;
}

// OpenEXR allocates what a header declares before it can notice that the file is shorter: an
// attribute size of 3 GB, or a data window whose line-offset table is gigabytes. Walk the header(s)
// first (magic, version, then name\0 type\0 int32-size value... up to an empty name; multi-part
// files repeat that until an empty header) and refuse sizes the file cannot hold.
void checkExrHeader(const std::string& path) {
  checkRegularFile(path, kMaxImageFileBytes, "EXR file");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw Error(path, 0, "cannot open EXR file");
  std::fseek(f, 0, SEEK_END);
  const long fileSize = std::ftell(f);
  std::fseek(f, 0, SEEK_SET);
  auto fail = [&](const std::string& why) {
    std::fclose(f);
    throw Error(path, 0, "cannot read EXR: " + why);
  };
  unsigned char head[8];
  if (std::fread(head, 1, 8, f) != 8 || head[0] != 0x76 || head[1] != 0x2f || head[2] != 0x31 ||
      head[3] != 0x01)
    fail("not an OpenEXR file (bad magic number)");
  const bool multiPart = head[5] & 0x10;
  auto readName = [&](std::string& out) {
    out.clear();
    for (int c; (c = std::fgetc(f)) != 0;) {
      if (c == EOF) fail("truncated header");
      if (out.size() >= 255) fail("header name longer than 255 characters");
      out += char(c);
    }
  };
  for (int part = 0;; ++part) {
    std::string name, type;
    readName(name);
    if (name.empty()) {
      if (!multiPart || part > 0) break;  // end of the (single) header, or of the header list
      fail("empty multi-part header");
    }
    for (; !name.empty(); readName(name)) {
      readName(type);
      unsigned char sizeBytes[4];
      if (std::fread(sizeBytes, 1, 4, f) != 4) fail("truncated header");
      const int32_t size = int32_t(uint32_t(sizeBytes[0]) | uint32_t(sizeBytes[1]) << 8 |
                                   uint32_t(sizeBytes[2]) << 16 | uint32_t(sizeBytes[3]) << 24);
      const long start = std::ftell(f), remaining = fileSize - start;
      if (size < 0 || long(size) > remaining)
        fail("attribute '" + name + "' declares " + std::to_string(size) + " bytes, the file has " +
             std::to_string(remaining) + " left");
      // OpenEXR reads typed values by their type, not by the declared size: where the two disagree
      // its reading and this walk would part ways, so such files are refused.
      const int fixed = fixedAttributeSize(type);
      if (fixed > 0 && size != fixed)
        fail("attribute '" + name + "' of type " + type + " declares " + std::to_string(size) +
             " bytes, expected " + std::to_string(fixed));
      if (type == "chlist") {
        std::string channel;
        for (readName(channel); !channel.empty(); readName(channel))
          if (std::fseek(f, 16, SEEK_CUR) != 0) fail("truncated channel list");
        if (std::ftell(f) - start != size)
          fail("channel list '" + name + "' does not match its declared size");
        continue;
      }
      if (type == "preview") {
        unsigned char wh[8];
        if (size < 8 || std::fread(wh, 1, 8, f) != 8) fail("truncated preview");
        const uint64_t w =
            uint32_t(wh[0]) | uint32_t(wh[1]) << 8 | uint32_t(wh[2]) << 16 | uint32_t(wh[3]) << 24;
        const uint64_t h =
            uint32_t(wh[4]) | uint32_t(wh[5]) << 8 | uint32_t(wh[6]) << 16 | uint32_t(wh[7]) << 24;
        if (8 + 4 * w * h != uint64_t(size)) fail("preview image does not match its declared size");
        std::fseek(f, size - 8, SEEK_CUR);
        continue;
      }
      if (name == "dataWindow" && type == "box2i") {
        unsigned char raw[16];
        if (std::fread(raw, 1, 16, f) != 16) fail("truncated header");
        int32_t box[4];  // little-endian xMin, yMin, xMax, yMax
        for (int i = 0; i < 4; ++i)
          box[i] = int32_t(uint32_t(raw[4 * i]) | uint32_t(raw[4 * i + 1]) << 8 |
                           uint32_t(raw[4 * i + 2]) << 16 | uint32_t(raw[4 * i + 3]) << 24);
        const int64_t w = int64_t(box[2]) - box[0] + 1, h = int64_t(box[3]) - box[1] + 1;
        // w and h may each be near 2^32: compare by division, since w * h can overflow int64.
        if (w <= 0 || h <= 0 || w > kMaxReadPixels || h > kMaxReadPixels / w)
          fail("data window " + std::to_string(w) + "x" + std::to_string(h) + " is empty or larger than " +
               std::to_string(kMaxReadPixels) + " pixels");
      } else {
        std::fseek(f, size, SEEK_CUR);
      }
    }
    if (!multiPart) break;
  }
  std::fclose(f);
}

void ignoreExrCoreError(exr_const_context_t, exr_result_t, const char*) {}

// Every chunk of the first part's level-0 image must have a valid entry in the chunk offset table
// (OpenEXR's core library checks each entry against the file's size). A corrupt file declaring a huge
// data window in a few hundred bytes is then refused before memory for the window is allocated; the
// C++ library would allocate first and notice the missing chunks while reading them.
void checkExrChunks(const std::string& path) {
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = ignoreExrCoreError;
  exr_context_t context = nullptr;
  if (exr_start_read(&context, path.c_str(), &init) != EXR_ERR_SUCCESS) {
    exr_finish(&context);
    return;  // the C++ library reports what is wrong with the header
  }
  exr_storage_t storage{};
  exr_attr_box2i_t window{};
  const bool ok = exr_get_storage(context, 0, &storage) == EXR_ERR_SUCCESS &&
                  exr_get_data_window(context, 0, &window) == EXR_ERR_SUCCESS;
  std::string missing;
  exr_chunk_info_t chunk;
  if (ok && storage == EXR_STORAGE_SCANLINE) {
    int32_t linesPerChunk = 0;
    if (exr_get_scanlines_per_chunk(context, 0, &linesPerChunk) != EXR_ERR_SUCCESS || linesPerChunk < 1)
      linesPerChunk = 1;
    for (int64_t y = window.min.y; y <= window.max.y && missing.empty(); y += linesPerChunk)
      if (exr_read_scanline_chunk_info(context, 0, int(y), &chunk) != EXR_ERR_SUCCESS)
        missing = "scan line " + std::to_string(y);
  } else if (ok && storage == EXR_STORAGE_TILED) {
    int32_t tileW = 0, tileH = 0;
    if (exr_get_tile_sizes(context, 0, 0, 0, &tileW, &tileH) == EXR_ERR_SUCCESS && tileW > 0 && tileH > 0) {
      const int64_t tilesX = (int64_t(window.max.x) - window.min.x + tileW) / tileW;
      const int64_t tilesY = (int64_t(window.max.y) - window.min.y + tileH) / tileH;
      for (int64_t ty = 0; ty < tilesY && missing.empty(); ++ty)
        for (int64_t tx = 0; tx < tilesX && missing.empty(); ++tx)
          if (exr_read_tile_chunk_info(context, 0, int(tx), int(ty), 0, 0, &chunk) != EXR_ERR_SUCCESS)
            missing = "tile (" + std::to_string(tx) + ", " + std::to_string(ty) + ")";
    }
  }
  exr_finish(&context);
  if (!missing.empty())
    throw Error(
        path, 0,
        "EXR is incomplete or corrupt: the chunk of " + missing + " is missing or lies outside the file");
}

}  // namespace

Image readExr(const std::string& path, ImageMetadata* metadata) {
  checkExrHeader(path);
  checkExrChunks(path);
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
    // Slices are addressed by absolute data-window coordinates; Slice::Make offsets the pointer by
    // the window's origin in integer arithmetic (the same offset as a char* would overflow for an
    // origin far from zero: undefined behaviour).
    const float* pixels = image.rgb.data();
    Imf::FrameBuffer fb;
    if (rgb) {
      // Missing colour channels are filled with 0.
      fb.insert("R", Imf::Slice::Make(Imf::FLOAT, pixels + 0, dw, xStride, yStride, 1, 1, 0.0));
      fb.insert("G", Imf::Slice::Make(Imf::FLOAT, pixels + 1, dw, xStride, yStride, 1, 1, 0.0));
      fb.insert("B", Imf::Slice::Make(Imf::FLOAT, pixels + 2, dw, xStride, yStride, 1, 1, 0.0));
    } else {
      fb.insert("Y", Imf::Slice::Make(Imf::FLOAT, pixels, dw, xStride, yStride, 1, 1, 0.0));
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
  checkExrHeader(path);
  try {
    Imf::InputFile file(path.c_str());
    return stringAttributes(file.header());
  } catch (const std::exception& e) {
    throw Error(path, 0, std::string("cannot read EXR: ") + e.what());
  }
}

}  // namespace penumbra
