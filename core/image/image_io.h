// Reading and writing images, dispatched on the file extension (case-insensitive):
//   .exr  32-bit float RGB, ZIP compression (or none, on request), metadata as string attributes (read: any
//   RGB/RGBA/Y,
//         half/float/uint channels; A is ignored, missing R/G/B are 0, Y is replicated; the image is
//         the data window; only string attributes come back as metadata)
//   .pfm  little-endian "PF" colour, bottom row first (read: "PF"/"Pf", either endianness)
//   .png  8-bit sRGB via toSrgb8 (tonemap.h); NaN/Inf become 0; metadata is not stored
//         (read: any PNG, converted to 8-bit sRGB RGB by libpng, then decoded to linear exactly)
// All writes are atomic (atomic_file.h): the target is replaced completely or left untouched. A
// replaced file gets default permissions (0666 & ~umask), not the old file's.
#pragma once

#include <cstdint>
#include <string>

#include "core/image/image.h"

namespace penumbra {

enum class ImageFormat { Exr, Pfm, Png };

// Readers refuse larger images (8192 x 8192; 768 MB as float RGB) and files, before allocating:
// a corrupt header must not make a few bytes claim gigabytes.
inline constexpr int64_t kMaxReadPixels = int64_t(1) << 26;
inline constexpr uint64_t kMaxImageFileBytes = uint64_t(4) << 30;
// EXR channel type on output: Float (default, lossless) or Half (previews; also used by tests to
// produce half inputs).
enum class ExrPixelType { Float, Half };
// EXR compression on output: Zip (default; lossless, ~10x smaller for renders) or None (several times
// faster to write: for a write that has a deadline, such as an interrupted render's).
enum class ExrCompression { Zip, None };

// Throws Error listing the supported extensions for anything else.
ImageFormat imageFormatFromPath(const std::string& path);

// `exposureStops` only affects PNG output.
void writeImage(const std::string& path, const Image& image, const ImageMetadata& metadata = {},
                float exposureStops = 0.f);
Image readImage(const std::string& path);
// Metadata stored in the file: EXR string attributes; PFM and PNG carry none (empty result).
ImageMetadata readImageMetadata(const std::string& path);

// Per-format entry points (writes are atomic).
void writeExr(const std::string& path, const Image& image, const ImageMetadata& metadata = {},
              ExrPixelType pixelType = ExrPixelType::Float, ExrCompression compression = ExrCompression::Zip);
Image readExr(const std::string& path, ImageMetadata* metadata = nullptr);
ImageMetadata readExrMetadata(const std::string& path);  // header only, no pixels
void writePfm(const std::string& path, const Image& image);
Image readPfm(const std::string& path);
void writePng(const std::string& path, const Image& image, const ImageMetadata& metadata = {},
              float exposureStops = 0.f);
Image readPng(const std::string& path);

}  // namespace penumbra
