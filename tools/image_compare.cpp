// For the end-to-end tests of penumbra-mpi:
//   penumbra_image_compare A B REL [Y0 Y1]
//                                    exit 0 when every channel of every pixel (of the rows [Y0, Y1)
//                                    only, if given) agrees within REL relative
//                                    (|a - b| <= REL * max(|a|, |b|)), else 1; prints the worst
//   penumbra_image_compare --info A  prints the metadata (key=value lines) and "valid=1" when every
//                                    value is finite and non-negative
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "core/image/image_io.h"

using namespace penumbra;

int main(int argc, char** argv) {
  try {
    if (argc == 3 && std::string(argv[1]) == "--info") {
      for (const auto& [k, v] : readImageMetadata(argv[2]).entries)
        std::printf("%s=%s\n", k.c_str(), v.c_str());
      const Image img = readImage(argv[2]);
      bool valid = !img.rgb.empty();
      for (float v : img.rgb) valid = valid && std::isfinite(v) && v >= 0.f;
      std::printf("valid=%d\n", valid ? 1 : 0);
      return 0;
    }
    if (argc != 4 && argc != 6) {
      std::fprintf(stderr, "usage: penumbra_image_compare A B REL [Y0 Y1] | --info A\n");
      return 2;
    }
    const Image a = readImage(argv[1]), b = readImage(argv[2]);
    const double rel = std::atof(argv[3]);
    if (a.width != b.width || a.height != b.height) {
      std::printf("sizes differ: %dx%d vs %dx%d\n", a.width, a.height, b.width, b.height);
      return 1;
    }
    const int y0 = argc == 6 ? std::atoi(argv[4]) : 0, y1 = argc == 6 ? std::atoi(argv[5]) : a.height;
    if (y0 < 0 || y1 > a.height || y0 >= y1) {
      std::fprintf(stderr, "error: rows [%d, %d) are not within the image's %d rows\n", y0, y1, a.height);
      return 2;
    }
    double worst = 0;
    size_t bad = 0;
    const size_t begin = size_t(y0) * size_t(a.width) * 3, end = size_t(y1) * size_t(a.width) * 3;
    for (size_t i = begin; i < end; ++i) {
      const double x = a.rgb[i], y = b.rgb[i], scale = std::max(std::abs(x), std::abs(y));
      const double d = scale > 0 ? std::abs(x - y) / scale : 0.0;
      if (!(d <= rel)) ++bad;
      if (!(d <= worst)) worst = d;
    }
    std::printf("worst relative difference %.3g over %zu pixels, %zu values beyond %g\n", worst,
                (end - begin) / 3, bad, rel);
    return bad == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
