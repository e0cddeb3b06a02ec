#include "app/cli/convergence_report.h"

#include <cairo.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "app/cli/false_colour.h"
#include "core/image/atomic_file.h"
#include "core/image/tonemap.h"
#include "core/math/error.h"
#include "core/sampling/sampler_table.h"

namespace penumbra::cli {

namespace fs = std::filesystem;

namespace {

// Okabe-Ito colours (colour-blind safe), one per strategy.
const double kColors[][3] = {{0.84, 0.37, 0.0},  {0.0, 0.45, 0.70}, {0.0, 0.62, 0.45},
                             {0.80, 0.47, 0.65}, {0.90, 0.62, 0.0}, {0.34, 0.71, 0.91}};

// Through a unique temporary that is removed on any failure (core/image/atomic_file.h).
void savePng(cairo_surface_t* surface, const std::string& path) {
  cairo_surface_flush(surface);
  writeFileAtomically(path, [&](const std::string& temp) {
    const cairo_status_t status = cairo_surface_write_to_png(surface, temp.c_str());
    if (status != CAIRO_STATUS_SUCCESS)
      throw Error("cannot write " + path + ": " + cairo_status_to_string(status));
  });
}

void writeText(const std::string& path, const std::string& text) {
  writeBytesAtomically(path, text.data(), text.size());
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

void text(cairo_t* cr, double x, double y, const std::string& s, double size, double alignX = 0,
          double alignY = 0, bool bold = false) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_move_to(cr, x - alignX * e.width - e.x_bearing, y - alignY * e.height - e.y_bearing);
  cairo_show_text(cr, s.c_str());
}

// "10^k" with a superscript exponent.
void powerLabel(cairo_t* cr, double x, double y, int k, double size, double alignX, double alignY) {
  std::string base = "10", ex = std::to_string(k);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t eb, ee;
  cairo_text_extents(cr, base.c_str(), &eb);
  cairo_set_font_size(cr, size * 0.7);
  cairo_text_extents(cr, ex.c_str(), &ee);
  double w = eb.x_advance + ee.x_advance, h = eb.height;
  double x0 = x - alignX * w, y0 = y - alignY * h + h;
  cairo_set_font_size(cr, size);
  cairo_move_to(cr, x0, y0);
  cairo_show_text(cr, base.c_str());
  cairo_set_font_size(cr, size * 0.7);
  cairo_move_to(cr, x0 + eb.x_advance, y0 - h * 0.45);
  cairo_show_text(cr, ex.c_str());
}

struct Axes {
  double x0, y0, w, h;        // plot area in pixels (y0 = top)
  double lx0, lx1, ly0, ly1;  // log10 ranges
  double px(double v) const { return x0 + (std::log10(v) - lx0) / (lx1 - lx0) * w; }
  double py(double v) const { return y0 + h - (std::log10(v) - ly0) / (ly1 - ly0) * h; }
};

void drawAxes(cairo_t* cr, const Axes& a, const std::string& xLabel, const std::string& yLabel,
              const std::string& title) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_rectangle(cr, a.x0, a.y0, a.w, a.h);
  cairo_fill(cr);
  // Grid and ticks at every decade, minor ticks at 2..9.
  cairo_set_line_width(cr, 1);
  for (int axis = 0; axis < 2; ++axis) {
    double lo = axis == 0 ? a.lx0 : a.ly0, hi = axis == 0 ? a.lx1 : a.ly1;
    for (int k = int(std::floor(lo)); k <= int(std::ceil(hi)); ++k)
      for (int m = 1; m <= 9; ++m) {
        double lv = k + std::log10(double(m));
        if (lv < lo - 1e-9 || lv > hi + 1e-9) continue;
        double v = std::pow(10.0, lv);
        bool major = m == 1;
        cairo_set_source_rgb(cr, major ? 0.82 : 0.93, major ? 0.82 : 0.93, major ? 0.82 : 0.93);
        if (axis == 0) {
          double x = a.px(v);
          cairo_move_to(cr, x, a.y0);
          cairo_line_to(cr, x, a.y0 + a.h);
          cairo_stroke(cr);
          cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
          cairo_move_to(cr, x, a.y0 + a.h);
          cairo_line_to(cr, x, a.y0 + a.h + (major ? 6 : 3));
          cairo_stroke(cr);
          if (major)
            powerLabel(cr, x, a.y0 + a.h + 9, k, 13, 0.5, 0);
          else if ((m == 2 || m == 5) && hi - lo <= 2.01)
            text(cr, x, a.y0 + a.h + 9, fmt("%g", v), 11, 0.5, 0);
        } else {
          double y = a.py(v);
          cairo_move_to(cr, a.x0, y);
          cairo_line_to(cr, a.x0 + a.w, y);
          cairo_stroke(cr);
          cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
          cairo_move_to(cr, a.x0, y);
          cairo_line_to(cr, a.x0 - (major ? 6 : 3), y);
          cairo_stroke(cr);
          if (major)
            powerLabel(cr, a.x0 - 9, y, k, 13, 1, 0.5);
          else if ((m == 2 || m == 5) && hi - lo <= 2.01)
            text(cr, a.x0 - 9, y, fmt("%g", v), 11, 1, 0.5);
        }
      }
  }
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_rectangle(cr, a.x0, a.y0, a.w, a.h);
  cairo_stroke(cr);
  text(cr, a.x0 + a.w / 2, a.y0 + a.h + 34, xLabel, 14, 0.5, 0);
  cairo_save(cr);
  cairo_translate(cr, a.x0 - 52, a.y0 + a.h / 2);
  cairo_rotate(cr, -kPiD / 2);
  text(cr, 0, 0, yLabel, 14, 0.5, 0.5);
  cairo_restore(cr);
  text(cr, a.x0 + a.w / 2, a.y0 - 10, title, 15, 0.5, 1, true);
}

double xOf(const ConvergencePoint& p, const ReportInfo& info) {
  return info.sppMode ? double(p.spp) : info.cpuAxis ? p.cpuSeconds : p.seconds;
}

// Per-pixel squared error (mean over channels) of an image against the reference.
std::vector<double> squaredErrors(const Image& v, const Image& ref) {
  std::vector<double> e(ref.pixelCount());
  for (std::size_t p = 0; p < e.size(); ++p) {
    double s = 0;
    for (int c = 0; c < 3; ++c) {
      double d = double(v.rgb[3 * p + c]) - ref.rgb[3 * p + c];
      s += d * d;
    }
    e[p] = s / 3;
  }
  return e;
}

cairo_surface_t* surfaceFrom(const std::vector<uint8_t>& rgb, int w, int h) {
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  cairo_surface_flush(s);
  unsigned char* data = cairo_image_surface_get_data(s);
  int stride = cairo_image_surface_get_stride(s);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t* p = &rgb[(std::size_t(y) * w + x) * 3];
      uint32_t v = (uint32_t(p[0]) << 16) | (uint32_t(p[1]) << 8) | p[2];
      *reinterpret_cast<uint32_t*>(data + y * stride + x * 4) = v;
    }
  cairo_surface_mark_dirty(s);
  return s;
}

void drawScaled(cairo_t* cr, cairo_surface_t* img, int w, int h, double x, double y, double size) {
  double scale = size / std::max(w, h);
  cairo_save(cr);
  cairo_translate(cr, x, y);
  cairo_scale(cr, scale, scale);
  cairo_set_source_surface(cr, img, 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr), scale < 1 ? CAIRO_FILTER_GOOD : CAIRO_FILTER_NEAREST);
  cairo_paint(cr);
  cairo_restore(cr);
}

// Whether the runs cross several samplers (then every label names the sampler too).
bool severalSamplers(const std::vector<ConvergenceRun>& runs) {
  for (const ConvergenceRun& r : runs)
    if (r.sampler != runs.front().sampler) return true;
  return false;
}

std::string strategyTitle(const ConvergenceRun& r, bool withSampler) {
  return strategyShortName(r.integrator) +
         (withSampler ? std::string(" / ") + samplerKindName(r.sampler) : "");
}

// One colour per strategy, one line style per sampler, in order of first appearance.
template <class Key>
std::size_t indexOf(std::vector<Key>& seen, const Key& k) {
  auto it = std::find(seen.begin(), seen.end(), k);
  if (it != seen.end()) return std::size_t(it - seen.begin());
  seen.push_back(k);
  return seen.size() - 1;
}
struct RunStyles {
  std::vector<std::size_t> colour, dash;
  std::vector<IntegratorDesc> strategies;
  std::vector<SamplerKind> samplers;
};
RunStyles runStyles(const std::vector<ConvergenceRun>& runs) {
  RunStyles st;
  for (const ConvergenceRun& r : runs) {
    st.colour.push_back(indexOf(st.strategies, r.integrator));
    st.dash.push_back(indexOf(st.samplers, r.sampler));
  }
  return st;
}
// Solid, dashed, dotted, dash-dotted.
void setDash(cairo_t* cr, std::size_t style) {
  static const double kDashes[][4] = {{0, 0, 0, 0}, {9, 5, 0, 0}, {2, 4, 0, 0}, {9, 4, 2, 4}};
  static const int kCounts[] = {0, 2, 2, 4};
  cairo_set_dash(cr, kDashes[style % 4], kCounts[style % 4], 0);
}

}  // namespace

void writeConvergenceCsv(const std::string& path, const std::vector<ConvergenceRun>& runs) {
  std::ostringstream out;
  out << "strategy,sampler,seconds,cpu_seconds,spp,samples,mse,rmse,rel_mse,mse_stderr,ref_variance,"
         "mse_nolight,rmse_nolight,rel_mse_nolight,mse_stderr_nolight\n";
  out.precision(9);
  for (const ConvergenceRun& r : runs)
    for (const ConvergencePoint& p : r.points)
      out << strategyShortName(r.integrator) << ',' << samplerKindName(r.sampler) << ',' << p.seconds << ','
          << p.cpuSeconds << ',' << p.spp << ',' << p.samples << ',' << p.error.all.mse << ','
          << p.error.all.rmse << ',' << p.error.all.relMse << ',' << p.error.all.mseStdErr << ','
          << p.error.all.refVariance << ',' << p.error.noLight.mse << ',' << p.error.noLight.rmse << ','
          << p.error.noLight.relMse << ',' << p.error.noLight.mseStdErr << '\n';
  writeText(path, out.str());
}

void plotConvergence(const std::string& path, const std::vector<ConvergenceRun>& runs,
                     const ReportInfo& info) {
  const int W = 1240, H = 590;
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 0.97, 0.97, 0.97);
  cairo_paint(cr);

  const RunStyles styles = runStyles(runs);
  for (int panel = 0; panel < 2; ++panel) {
    bool noLight = panel == 1;
    auto rmseOf = [&](const ConvergencePoint& p) {
      return noLight ? p.error.noLight.rmse : p.error.all.rmse;
    };
    double xmin = INFINITY, xmax = 0, ymin = INFINITY, ymax = 0;
    for (const ConvergenceRun& r : runs)
      for (const ConvergencePoint& p : r.points) {
        double x = xOf(p, info), y = rmseOf(p);
        if (!(x > 0) || !(y > 0)) continue;
        xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y),
        ymax = std::max(ymax, y);
      }
    if (!(xmax > 0)) xmin = 1e-3, xmax = 1, ymin = 1e-3, ymax = 1;
    Axes a{95.0 + panel * 590.0,
           50.0,
           470.0,
           double(H) - 190.0,
           std::floor(std::log10(xmin) * 2) / 2,
           std::ceil(std::log10(xmax) * 2) / 2,
           std::floor(std::log10(ymin) * 2) / 2,
           std::ceil(std::log10(ymax) * 2) / 2};
    if (a.lx1 - a.lx0 < 1) a.lx1 = a.lx0 + 1;
    if (a.ly1 - a.ly0 < 1) a.ly1 = a.ly0 + 1;
    std::string title =
        noLight ? "pixels that see no light directly (" + std::to_string(info.noLightPixels) + " px)"
                : "all pixels (" + std::to_string(info.pixels) + " px)";
    drawAxes(cr, a,
             info.sppMode   ? "samples per pixel"
             : info.cpuAxis ? "CPU time of the render (seconds, summed over threads)"
                            : "render time (wall-clock seconds, all cores)",
             "RMSE", title);

    cairo_save(cr);
    cairo_rectangle(cr, a.x0, a.y0, a.w, a.h);
    cairo_clip(cr);
    // -1/2 slope guide through the geometric middle of the data.
    {
      double lxm = (std::log10(xmin) + std::log10(xmax)) / 2, lym = (std::log10(ymin) + std::log10(ymax)) / 2;
      double lxa = a.lx0, lxb = a.lx1;
      cairo_set_source_rgb(cr, 0.45, 0.45, 0.45);
      cairo_set_line_width(cr, 1.5);
      double dash[] = {6, 5};
      cairo_set_dash(cr, dash, 2, 0);
      cairo_move_to(cr, a.px(std::pow(10, lxa)), a.py(std::pow(10, lym - 0.5 * (lxa - lxm))));
      cairo_line_to(cr, a.px(std::pow(10, lxb)), a.py(std::pow(10, lym - 0.5 * (lxb - lxm))));
      cairo_stroke(cr);
      cairo_set_dash(cr, nullptr, 0, 0);
      double lxt = lxm + 0.25 * (a.lx1 - a.lx0) * 0.5;
      text(cr, a.px(std::pow(10, lxt)) + 4, a.py(std::pow(10, lym - 0.5 * (lxt - lxm))) + 4, "slope -1/2", 12,
           0, 0);
    }
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const double* c = kColors[styles.colour[i] % 6];
      cairo_set_source_rgb(cr, c[0], c[1], c[2]);
      cairo_set_line_width(cr, 2.2);
      setDash(cr, styles.dash[i]);
      bool started = false;
      for (const ConvergencePoint& p : runs[i].points) {
        double x = xOf(p, info), y = rmseOf(p);
        if (!(x > 0) || !(y > 0)) continue;
        if (!started)
          cairo_move_to(cr, a.px(x), a.py(y));
        else
          cairo_line_to(cr, a.px(x), a.py(y));
        started = true;
      }
      cairo_stroke(cr);
      cairo_set_dash(cr, nullptr, 0, 0);
      // Markers with ±1 standard error bars (RMSE error from the MSE's: se/(2 RMSE)).
      cairo_set_line_width(cr, 1.2);
      for (const ConvergencePoint& p : runs[i].points) {
        double x = xOf(p, info), y = rmseOf(p);
        if (!(x > 0) || !(y > 0)) continue;
        const ErrorStats& s = noLight ? p.error.noLight : p.error.all;
        double se = s.mseStdErr / (2 * y);
        cairo_arc(cr, a.px(x), a.py(y), 2.8, 0, 2 * kPiD);
        cairo_fill(cr);
        if (se > 0) {
          cairo_move_to(cr, a.px(x), a.py(y + se));
          cairo_line_to(cr, a.px(x), a.py(std::max(y - se, y * 0.05)));
          cairo_stroke(cr);
        }
      }
    }
    cairo_restore(cr);
  }
  // Legend along the bottom: a colour per strategy; with several samplers, a line style per sampler.
  double lx = 95, ly = H - 58;
  auto legendEntry = [&](const double* c, std::size_t dash, const std::string& label) {
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_set_line_width(cr, 3);
    setDash(cr, dash);
    cairo_move_to(cr, lx, ly);
    cairo_line_to(cr, lx + 30, ly);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    text(cr, lx + 36, ly, label, 14, 0, 0.5);
    cairo_text_extents_t e;
    cairo_text_extents(cr, label.c_str(), &e);
    lx += 36 + e.x_advance + 26;
  };
  for (std::size_t k = 0; k < styles.strategies.size(); ++k)
    for (std::size_t i = 0; i < runs.size(); ++i)
      if (styles.colour[i] == k) {
        legendEntry(kColors[k % 6], 0, runs[i].strategy);
        break;
      }
  if (styles.samplers.size() > 1) {
    static const double kGrey[3] = {0.35, 0.35, 0.35};
    lx += 20;
    for (std::size_t k = 0; k < styles.samplers.size(); ++k)
      legendEntry(kGrey, k, samplerKindName(styles.samplers[k]));
  }
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  std::string caption = info.sceneName + ", " + std::to_string(info.width) + "x" +
                        std::to_string(info.height) + ", reference: " + info.referenceSource;
  text(cr, 95, H - 22, caption, 12, 0, 0.5);
  cairo_destroy(cr);
  savePng(surface, path);
  cairo_surface_destroy(surface);
}

void writeEqualTimeImage(const std::string& path, const std::vector<ConvergenceRun>& runs,
                         const Reference& ref, const ReportInfo& info) {
  const int n = int(runs.size()) + 1;  // + the reference
  const double tile = 240, gap = 14, top = 44, labelH = 46;
  const int W = int(gap + n * (tile + gap)), H = int(top + 2 * (tile + labelH) + 30);
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 0.97, 0.97, 0.97);
  cairo_paint(cr);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  std::string head = info.sppMode ? "Equal samples (" + fmt("%.0f", info.budget) + " spp each)"
                                  : "Equal time (" + fmt("%.3g", info.budget) + " s each)";
  text(cr, W / 2.0, 14, head + ": images (top) and per-pixel squared error against the reference (bottom)",
       15, 0.5, 0, true);

  // Shared log scale for the error maps: 1st to 99.5th percentile of positive errors over all runs.
  std::vector<std::vector<double>> errs;
  std::vector<double> pool;
  for (const ConvergenceRun& r : runs) {
    errs.push_back(squaredErrors(r.finalImage, ref.mean));
    for (double e : errs.back())
      if (e > 0 && std::isfinite(e)) pool.push_back(std::log10(e));
  }
  double lo = -6, hi = 0;
  if (!pool.empty()) {
    std::sort(pool.begin(), pool.end());
    lo = pool[std::size_t(0.01 * (pool.size() - 1))];
    hi = pool[std::size_t(0.995 * (pool.size() - 1))];
    if (hi - lo < 1) lo = hi - 1;
    lo = std::max(lo, hi - 8);  // 8 decades: below that, black
  }
  const int w = ref.mean.width, h = ref.mean.height;
  for (int i = 0; i < n; ++i) {
    double x = gap + i * (tile + gap);
    bool isRef = i == n - 1;
    const Image& img = isRef ? ref.mean : runs[i].finalImage;
    cairo_surface_t* s = surfaceFrom(toSrgb8(img), w, h);
    drawScaled(cr, s, w, h, x, top, tile);
    cairo_surface_destroy(s);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    if (isRef) {
      text(cr, x + tile / 2, top + tile + 6, "reference", 14, 0.5, 0, true);
      // "cache scenes/x/y.xml.ref-HASH.exr (rendered ...)": the file name only, then how it was made.
      std::string src = info.referenceSource, how;
      if (size_t open = src.find(" ("); open != std::string::npos)
        how = src.substr(open + 2, src.size() - open - 3), src.resize(open);
      if (size_t sp = src.find(' '); sp != std::string::npos)
        src = src.substr(0, sp + 1) + fs::path(src.substr(sp + 1)).filename().string();
      if (src.size() > 40) src = src.substr(0, 18) + "..." + src.substr(src.size() - 19);
      text(cr, x + tile / 2, top + tile + 24, src, 11, 0.5, 0);
      if (!how.empty()) text(cr, x + tile / 2, top + tile + 38, how, 11, 0.5, 0);
      continue;
    }
    const ConvergenceRun& r = runs[i];
    const ConvergencePoint& last = r.points.back();
    text(cr, x + tile / 2, top + tile + 6, strategyTitle(r, severalSamplers(runs)), 14, 0.5, 0, true);
    text(cr, x + tile / 2, top + tile + 26,
         std::to_string(r.spp) + " spp, " + fmt("%.2f s", r.seconds) + ", RMSE " +
             fmt("%.3g", last.error.all.rmse),
         12, 0.5, 0);
    std::vector<uint8_t> rgb(std::size_t(w) * h * 3);
    for (std::size_t p = 0; p < errs[i].size(); ++p) {
      const Rgb c = falseColour(errs[i][p] > 0 ? (std::log10(errs[i][p]) - lo) / (hi - lo) : 0);
      rgb[3 * p] = uint8_t(c.r * 255 + 0.5), rgb[3 * p + 1] = uint8_t(c.g * 255 + 0.5),
              rgb[3 * p + 2] = uint8_t(c.b * 255 + 0.5);
    }
    s = surfaceFrom(rgb, w, h);
    double y2 = top + tile + labelH;
    drawScaled(cr, s, w, h, x, y2, tile);
    cairo_surface_destroy(s);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    text(cr, x + tile / 2, y2 + tile + 6, "no-light RMSE " + fmt("%.3g", last.error.noLight.rmse), 12, 0.5,
         0);
  }
  // Colour bar under the reference column.
  double bx = gap + (n - 1) * (tile + gap), by = top + tile + labelH + 40, bw = tile, bh = 18;
  for (int k = 0; k < int(bw); ++k) {
    const Rgb c = falseColour(k / bw);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_rectangle(cr, bx + k, by, 1, bh);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  text(cr, bx + bw / 2, by - 6, "squared error (log scale)", 12, 0.5, 1);
  int step = std::max(1, int(std::ceil(36.0 / (bw / (hi - lo)))));  // labels >= 36 px apart
  for (int k = int(std::ceil(lo)); k <= int(std::floor(hi)); ++k) {
    if (k % step != 0) continue;
    double px = bx + (k - lo) / (hi - lo) * bw;
    cairo_move_to(cr, px, by + bh);
    cairo_line_to(cr, px, by + bh + 5);
    cairo_set_line_width(cr, 1);
    cairo_stroke(cr);
    powerLabel(cr, px, by + bh + 8, k, 12, 0.5, 0);
  }
  text(cr, bx, by + bh + 40, "black: below " + fmt("%.1e", std::pow(10, lo)), 11, 0, 0);
  text(cr, W / 2.0, H - 16,
       info.sceneName + ", " + std::to_string(w) + "x" + std::to_string(h) + ", sRGB, no exposure change", 11,
       0.5, 0.5);
  cairo_destroy(cr);
  savePng(surface, path);
  cairo_surface_destroy(surface);
}

void writeSummary(const std::string& path, const std::vector<ConvergenceRun>& runs, const ReportInfo& info) {
  std::ostringstream out;
  out << "# Convergence: " << info.sceneName << "\n\n";
  out << "- image: " << info.width << "x" << info.height << " (" << info.pixels << " px; "
      << info.noLightPixels << " see no light directly)\n";
  out << "- budget: " << (info.sppMode ? fmt("%.0f spp", info.budget) : fmt("%.3g s", info.budget))
      << " per strategy and sampler, each from a cold start on "
      << (info.threads > 0 ? std::to_string(info.threads) : std::string("all"))
      << " threads, one after another\n";
  out << "- reference: " << info.referenceSource << "\n";
  out << "- efficiency = 1 / (MSE x seconds), from the geometric mean of MSE x seconds over the last decade "
         "of "
         "each run; speed-up = efficiency / efficiency of uniform hemisphere sampling (the time uniform "
         "hemisphere sampling needs to reach the same MSE, divided by this strategy's).\n";
  out << "- wall: wall-clock seconds (what a user waits); CPU: the render's CPU seconds, which do not grow "
         "while "
         "other processes hold the cores, so the CPU speed-ups are the stable ones on a shared machine.\n";
  out << "- no-light: only pixels that see no emitter directly (the emitter's silhouette pixels have a large "
         "variance from the pixel filter alone, the same for every strategy, and dominate the all-pixel "
         "MSE).\n\n";
  out << "- slope: least-squares slope of log MSE against log " << (info.sppMode ? "spp" : "time")
      << " over each run's points from its 4th pass on. Independent samples give -1 (MSE ~ 1/N); a "
         "sampler whose nets pay off gives a steeper slope (Owen-scrambled Sobol': down to -2 or -3 on "
         "smooth pixels), until edges, occlusion and the pixel filter's discontinuities bring it back "
         "towards -1. The all-pixel slope mixes both; the no-light one leaves out the emitter's "
         "silhouette.\n\n";
  // Speed-ups are against the baseline strategy with the first sampler listed.
  const ConvergenceRun* base = nullptr;
  for (const ConvergenceRun& r : runs)
    if (isBaseline(r.integrator) && r.sampler == runs.front().sampler) base = &r;
  out << "| strategy | sampler | spp | wall s | CPU s | MSE | RMSE | relMSE | slope | slope (CPU) | "
         "efficiency (wall) | speed-up (wall) | speed-up (CPU) | MSE no-light | slope no-light | "
         "efficiency no-light (wall) | speed-up no-light (wall) | speed-up no-light (CPU) |\n";
  out << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  auto slopeText = [](double v) { return std::isfinite(v) ? fmt("%.2f", v) : std::string("n/a"); };
  auto ratio = [&](double e, double eb) {
    return base && eb > 0 ? fmt("%.3gx", e / eb) : std::string("n/a");
  };
  for (const ConvergenceRun& r : runs) {
    const ConvergencePoint& p = r.points.back();
    double e = efficiency(r), en = efficiency(r, true), ec = efficiency(r, false, true),
           enc = efficiency(r, true, true);
    double b = base ? efficiency(*base) : 0, bn = base ? efficiency(*base, true) : 0;
    double bc = base ? efficiency(*base, false, true) : 0, bnc = base ? efficiency(*base, true, true) : 0;
    out << "| " << strategyShortName(r.integrator) << " | " << samplerKindName(r.sampler) << " | " << r.spp
        << " | " << fmt("%.2f", r.seconds) << " | " << fmt("%.2f", p.cpuSeconds) << " | "
        << fmt("%.3e", p.error.all.mse) << " | " << fmt("%.3e", p.error.all.rmse) << " | "
        << fmt("%.3e", p.error.all.relMse) << " | " << slopeText(mseSlope(r, info.sppMode)) << " | "
        << slopeText(mseSlope(r, info.sppMode, false, true)) << " | " << fmt("%.4g", e) << " | "
        << ratio(e, b) << " | " << ratio(ec, bc) << " | " << fmt("%.3e", p.error.noLight.mse) << " | "
        << slopeText(mseSlope(r, info.sppMode, true)) << " | " << fmt("%.4g", en) << " | " << ratio(en, bn)
        << " | " << ratio(enc, bnc) << " |\n";
  }
  if (!base && !runs.empty())
    out << "\n(uniform hemisphere sampling was not run with " << samplerKindName(runs.front().sampler)
        << ", so there is no speed-up column.)\n";
  out << "\nFiles: convergence.csv (every measurement), convergence.png (RMSE against "
      << (info.sppMode ? "spp" : "time") << ", log-log), equal-time.png (final images and error maps).\n";
  writeText(path, out.str());
}

}  // namespace penumbra::cli
