// `penumbra warp --gui`: the warp inspector in its own window, or offscreen (penumbra-offscreen,
// OSMesa) with --offscreen or without a display, by the same re-execution as `penumbra view`.
// Compiled into the executables with the viewer (it needs GL), like view_command.cpp.
#include <cstdio>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "app/platform/offscreen_exec.h"
#include "app/platform/platform.h"
#include "app/ui/warp_inspector.h"
#include "core/math/error.h"
#include "core/sampling/sampler_table.h"

namespace penumbra::cli {

namespace {

constexpr const char* kFallbackScreenshot = "penumbra-warp.png";

// This command's arguments for penumbra-offscreen.
std::vector<std::string> offscreenArgs(const WarpGuiArgs& g) {
  char param[32];
  std::snprintf(param, sizeof param, "%.9g", g.param);
  std::vector<std::string> args = {"warp",
                                   g.bsdf ? g.bsdf->type : std::string(warpTypeName(g.type)),
                                   "--gui",
                                   "--points",
                                   std::to_string(g.log2Points),
                                   "--point-set",
                                   g.pointSet,
                                   "--seed",
                                   std::to_string(g.seed)};
  if (g.bsdf) {
    char v[32];
    auto number = [&](double x) { return std::snprintf(v, sizeof v, "%.9g", x), std::string(v); };
    args.insert(args.end(),
                {"--param", number(g.bsdf->alpha), "--incident", number(g.bsdf->incidentDegrees)});
    if (g.bsdf->type == "microfacet")
      args.insert(args.end(), {"--kd", number(g.bsdf->kd), "--int-ior", number(g.bsdf->intIOR), "--ext-ior",
                               number(g.bsdf->extIOR)});
    else
      args.insert(args.end(), {"--distribution", g.bsdf->distribution});
  } else if (warpHasParameter(g.type)) {
    args.insert(args.end(), {"--param", param});
  }
  if (g.pointSet == "sampler")
    args.insert(args.end(), {"--sampler", g.sampler, "--request", std::to_string(g.request), "--pixel",
                             std::to_string(g.pixelX) + "," + std::to_string(g.pixelY)});
  if (g.mismatch) args.push_back("--mismatch");
  if (g.gridLines) args.push_back("--grid-lines");
  if (g.res > 0) args.insert(args.end(), {"--res", std::to_string(g.res)});
  if (g.frames >= 0) args.insert(args.end(), {"--frames", std::to_string(g.frames)});
  args.insert(args.end(), {"--screenshot", g.screenshot.empty() ? kFallbackScreenshot : g.screenshot});
  if (!g.window.empty()) args.insert(args.end(), {"--window", g.window});
  if (g.noWait) args.push_back("--no-wait");
  if (g.printLayout) args.push_back("--print-layout");
  return args;
}

}  // namespace

int runWarpGui(const WarpGuiArgs& in) {
  const WarpGuiArgs& g = in;
  ui::WarpGuiOptions o;
  if (!ui::parsePointSet(g.pointSet, o.settings.pointSet))
    throw Error("--point-set " + g.pointSet + ": expected independent, grid, stratified or sampler");
  if (!parseSamplerKind(g.sampler, o.settings.sampler))
    throw Error("--sampler " + g.sampler + ": expected one of " + acceptedSamplerNames());
  o.settings.request = g.request;
  o.settings.pixelX = g.pixelX;
  o.settings.pixelY = g.pixelY;
  const bool offscreenBuild = platform::isOffscreenBuild();
  platform::runOffscreenUnlessWindowed("penumbra warp --gui", g.offscreen,
                                       g.screenshot.empty() ? kFallbackScreenshot : g.screenshot,
                                       [&] { return offscreenArgs(g); });
  o.settings.type = g.type;
  o.settings.param = warpHasParameter(g.type) ? g.param : 0.f;
  if (g.bsdf) {
    const std::string refused = ui::enterBsdf(o.settings, *g.bsdf);
    if (!refused.empty()) throw Error(refused);
  }
  o.settings.log2Points = g.log2Points;
  o.settings.mismatch = g.mismatch;
  o.settings.gridLines = g.gridLines;
  o.settings.seed = g.seed;
  o.settings.resolution = g.res;
  o.screenshot = g.screenshot;
  if (offscreenBuild && o.screenshot.empty()) o.screenshot = kFallbackScreenshot;
  o.frames = g.frames >= 0 ? g.frames : (offscreenBuild ? 3 : 0);
  o.waitForResult = offscreenBuild && !g.noWait;
  o.printLayout = g.printLayout;
  if (!g.window.empty() && (std::sscanf(g.window.c_str(), "%dx%d", &o.windowWidth, &o.windowHeight) != 2 ||
                            o.windowWidth < 320 || o.windowHeight < 240))
    throw Error("--window " + g.window + ": expected WIDTHxHEIGHT, e.g. 1280x800");
  return ui::runWarpInspector(o);
}

}  // namespace penumbra::cli
