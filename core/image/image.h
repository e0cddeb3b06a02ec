// A plain linear-RGB float image (row-major, top row first, 3 floats per pixel) and the key/value
// metadata that image files carry alongside it (spp, seconds, integrator settings, seed, ...).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/math/vec.h"

namespace penumbra {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  // row-major, top row first, 3 floats per pixel

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0.f) {}

  std::size_t index(int x, int y) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
  }
  Color3 at(int x, int y) const {
    std::size_t i = index(x, y);
    return Color3(rgb[i], rgb[i + 1], rgb[i + 2]);
  }
  void set(int x, int y, const Color3& c) {
    std::size_t i = index(x, y);
    rgb[i] = c.x;
    rgb[i + 1] = c.y;
    rgb[i + 2] = c.z;
  }
  std::size_t pixelCount() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  bool empty() const { return width <= 0 || height <= 0; }
};

struct ImageMetadata {
  std::vector<std::pair<std::string, std::string>> entries;

  void add(std::string key, std::string value) { entries.emplace_back(std::move(key), std::move(value)); }
  // First value stored under `key`, or nullptr.
  const std::string* find(const std::string& key) const {
    for (const auto& [k, v] : entries)
      if (k == key) return &v;
    return nullptr;
  }
};

}  // namespace penumbra
