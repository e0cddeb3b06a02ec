// Builds a contact sheet: pairs of images side by side (ours | reference), one pair per row, each
// scaled down by an integer factor and tone mapped like `penumbra render -o x.png`, and prints the
// mean of every image. Usage:
//   penumbra_contact_sheet OUT.png SCALE A1.exr B1.exr [A2.exr B2.exr ...]
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/image/image_io.h"

using namespace penumbra;

namespace {

Image downscale(const Image& in, int factor) {
  Image out(in.width / factor, in.height / factor);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      Color3 sum(0.f);
      for (int j = 0; j < factor; ++j)
        for (int i = 0; i < factor; ++i) sum += in.at(x * factor + i, y * factor + j);
      out.set(x, y, sum / float(factor * factor));
    }
  return out;
}

double mean(const Image& img) {
  double s = 0;
  for (float v : img.rgb) s += v;
  return img.rgb.empty() ? 0 : s / double(img.rgb.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5 || (argc - 3) % 2 != 0) {
    std::fprintf(stderr, "usage: %s OUT.png SCALE A1 B1 [A2 B2 ...]\n", argv[0]);
    return 2;
  }
  const int factor = std::atoi(argv[2]);
  const int gap = 8;
  std::vector<Image> cells;
  for (int i = 3; i < argc; ++i) {
    Image img = readImage(argv[i]);
    std::printf("%-60s %dx%d mean %.4f\n", argv[i], img.width, img.height, mean(img));
    cells.push_back(downscale(img, factor));
  }
  const int cw = cells[0].width, ch = cells[0].height, rows = int(cells.size()) / 2;
  Image sheet(2 * cw + 3 * gap, rows * ch + (rows + 1) * gap);
  for (float& v : sheet.rgb) v = 0.18f;  // mid-grey frame
  for (size_t k = 0; k < cells.size(); ++k) {
    int ox = gap + int(k % 2) * (cw + gap), oy = gap + int(k / 2) * (ch + gap);
    for (int y = 0; y < std::min(ch, cells[k].height); ++y)
      for (int x = 0; x < std::min(cw, cells[k].width); ++x) sheet.set(ox + x, oy + y, cells[k].at(x, y));
  }
  writeImage(argv[1], sheet);
  return 0;
}
