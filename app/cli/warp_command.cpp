// `penumbra warp`: chi-square tests of the sample warps, sample dumps and pdf evaluation.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "app/cli/option_checks.h"
#include "core/materials/bsdf_warp.h"
#include "core/math/error.h"
#include "core/math/float_util.h"
#include "core/sampling/chi2.h"
#include "core/sampling/rng.h"
#include "core/sampling/warp.h"
#include "core/sampling/warp_params.h"

namespace penumbra::cli {

namespace {

struct WarpArgs {
  std::string type;
  double param = 0.0;
  uint64_t samples = 1'000'000;
  int res = 51;
  uint64_t seed = 1;
  bool all = false;
  uint64_t dump = 0;
  bool pdf = false;
  std::string pdfOf;
  double pdfParam = 0.0;
  double pdfScale = 1.0;
  bool mismatch = false;
  BsdfWarpInputs bsdf;  // TYPE microfacet | roughconductor
  // --gui: the warp inspector
  bool gui = false;
  int points = 14;
  std::string pointSet = "independent";
  std::string pixel = "0,0";
  bool gridLines = false;
  WarpGuiArgs view;
};

// A deliberately wrong pdf for each warp (for --mismatch): the test must reject the pair.
void mismatchPartner(WarpType type, float param, WarpType& pdfType, float& pdfParam) {
  pdfParam = 0.f;
  switch (type) {
    case WarpType::UniformSquare:
      pdfType = WarpType::Tent;
      return;
    case WarpType::Tent:
      pdfType = WarpType::UniformSquare;
      return;
    case WarpType::UniformDisk:
    case WarpType::ConcentricDisk:
      pdfType = WarpType::Tent;
      return;
    case WarpType::UniformSphere:
    case WarpType::CosineHemisphere:
      pdfType = WarpType::UniformHemisphere;
      return;
    case WarpType::UniformHemisphere:
      pdfType = WarpType::CosineHemisphere;
      return;
    case WarpType::UniformCone:
      pdfType = WarpType::UniformCone;
      pdfParam = 0.5f * (param + 1.f);  // a narrower cone
      return;
    case WarpType::Beckmann:
      pdfType = WarpType::Beckmann;
      pdfParam = 2.f * param;
      return;
  }
}

std::string paramText(WarpType type, float param) {
  if (!warpHasParameter(type)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", param);
  return buf;
}

void dumpSamples(const SampleFunction& sample, uint64_t count, uint64_t seed) {
  Rng rng(mix64(seed), seed);  // the same stream the chi-square test draws from
  for (uint64_t i = 0; i < count; ++i) {
    float u1 = rng.nextFloat();
    Vec3 v = sample(Vec2(u1, rng.nextFloat()));
    std::printf("%.9g %.9g %.9g\n", v.x, v.y, v.z);
  }
}

void evaluatePdfs(const PdfFunction& pdf) {
  std::string line;
  int lineNo = 0;
  while (std::getline(std::cin, line)) {
    ++lineNo;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream in(line);
    float x, y, z;
    if (!(in >> x >> y >> z))
      throw Error("<stdin>", lineNo, "expected three numbers 'x y z', got '" + line + "'");
    std::printf("%.9g\n", pdf(Vec3(x, y, z)));
  }
}

void printVerdict(const Chi2Result& r) {
  std::printf("chi2      %.2f\n", r.chi2);
  std::printf("dof       %d\n", r.dof);
  std::printf("p-value   %.4g\n", r.pValue);
  std::printf("verdict   %s (alpha %.3g)%s%s\n", chi2Verdict(r), r.alphaEffective,
              r.message.empty() ? "" : ": ", r.message.c_str());
}

Chi2Options chi2OptionsOf(const WarpArgs& a) {
  Chi2Options opt;
  opt.sampleCount = a.samples;
  opt.resolution = a.res;
  opt.seed = a.seed;
  return opt;
}

int runSingle(const WarpArgs& a, const CLI::App& cmd) {
  WarpType type = parseWarpTypeOrThrow(a.type);
  float param = checkedWarpParam(type, cmd.count("--param") > 0, a.param, "--param");
  WarpType pdfType = type;
  float pdfParam = param;
  if (a.mismatch) {
    mismatchPartner(type, param, pdfType, pdfParam);
  } else if (!a.pdfOf.empty()) {
    pdfType = parseWarpTypeOrThrow(a.pdfOf);
    pdfParam = checkedWarpParam(pdfType, cmd.count("--pdf-param") > 0, a.pdfParam, "--pdf-param");
  }

  Chi2Result r = chi2Test(chi2DomainFor(pdfType, pdfParam), warpSampleFunction(type, param),
                          warpPdfFunction(pdfType, pdfParam, a.pdfScale), chi2OptionsOf(a));

  std::printf("warp      %s%s%s\n", warpTypeName(type), warpHasParameter(type) ? "  param " : "",
              warpHasParameter(type) ? paramText(type, param).c_str() : "");
  if (pdfType != type || pdfParam != param || a.pdfScale != 1.0)
    std::printf("pdf of    %s%s%s  x %g   (mismatched pair)\n", warpTypeName(pdfType),
                warpHasParameter(pdfType) ? "  param " : "",
                warpHasParameter(pdfType) ? paramText(pdfType, pdfParam).c_str() : "", a.pdfScale);
  std::printf("samples   %llu (seed %llu) in %d x %d cells + outside, %d pooled\n",
              static_cast<unsigned long long>(a.samples), static_cast<unsigned long long>(a.seed), r.resX,
              r.resY, r.pooledCells);
  printVerdict(r);
  return r.accepted ? 0 : 1;
}

// The BSDF inputs from the options; the BSDF options with another warp are an error.
BsdfWarp bsdfWarpOf(const WarpArgs& a, const CLI::App& cmd) {
  BsdfWarpInputs in = a.bsdf;
  in.type = a.type;
  if (cmd.count("--param")) in.alpha = a.param;
  if (in.type != "microfacet")
    for (const char* o : {"--kd", "--int-ior", "--ext-ior"})
      if (cmd.count(o)) throw Error(std::string(o) + " is a parameter of microfacet, not of " + in.type);
  if (in.type != "roughconductor" && cmd.count("--distribution"))
    throw Error("--distribution is a parameter of roughconductor, not of " + in.type);
  return checkedBsdfWarp(in);
}

// A deliberately wrong density for a BSDF (--mismatch): the lobe's density at twice its roughness.
BsdfWarp bsdfMismatchPartner(BsdfWarp w) {
  w.bsdf.alpha = std::min(2.f * w.bsdf.alpha, kMaxAlpha);
  return w;
}

int runBsdfSingle(const WarpArgs& a, const CLI::App& cmd) {
  if (!a.pdfOf.empty()) throw Error("--pdf-of judges by another warp's pdf; a BSDF takes --mismatch");
  const BsdfWarp warp = bsdfWarpOf(a, cmd);
  const BsdfWarp judge = a.mismatch ? bsdfMismatchPartner(warp) : warp;
  Chi2Options opt = chi2OptionsOf(a);
  opt.rejectedDraws = true;
  Chi2Result r =
      chi2Test(bsdfChi2Domain(), bsdfSampleFunction(warp), bsdfPdfFunction(judge, a.pdfScale), opt);
  std::printf("bsdf      %s\n", describeBsdfWarp(warp).c_str());
  if (a.mismatch || a.pdfScale != 1.0)
    std::printf("pdf of    %s  x %g   (mismatched pair)\n", describeBsdfWarp(judge).c_str(), a.pdfScale);
  std::printf(
      "samples   %llu (seed %llu) in %d x %d cells of the upper hemisphere + rejected draws, %d pooled\n",
      static_cast<unsigned long long>(a.samples), static_cast<unsigned long long>(a.seed), r.resX, r.resY,
      r.pooledCells);
  std::printf("rejected  %.0f draws (expected %.1f: the mass the pdf misses)\n", r.observedRejected,
              r.expectedRejected);
  printVerdict(r);
  return r.accepted ? 0 : 1;
}

struct Case {
  std::string name, label;
  Chi2Domain domain;
  SampleFunction sample;
  PdfFunction pdf;
  bool rejectedDraws = false;
};

Case warpCase(WarpType type, float param, std::string label) {
  return {warpTypeName(type),           std::move(label),
          chi2DomainFor(type, param),   warpSampleFunction(type, param),
          warpPdfFunction(type, param), false};
}

Case bsdfCase(const BsdfWarp& w) {
  char label[96];
  if (w.bsdf.type == BsdfType::Microfacet)
    std::snprintf(label, sizeof label, "a=%g kd=%g %g deg", w.bsdf.alpha, w.bsdf.albedo.x, w.incidentDegrees);
  else
    std::snprintf(label, sizeof label, "%s a=%g %g deg",
                  w.bsdf.distribution == MicrofacetDistribution::Ggx ? "ggx" : "beckmann", w.bsdf.alpha,
                  w.incidentDegrees);
  return {w.bsdf.type == BsdfType::Microfacet ? "microfacet" : "roughconductor",
          label,
          bsdfChi2Domain(),
          bsdfSampleFunction(w),
          bsdfPdfFunction(w),
          true};
}

std::vector<Case> allCases() {
  std::vector<Case> cases;
  for (int i = 0; i < kWarpTypeCount; ++i) {
    auto t = static_cast<WarpType>(i);
    if (!warpHasParameter(t)) cases.push_back(warpCase(t, 0.f, "-"));
  }
  for (float c : {-0.5f, 0.f, 0.5f, 0.9f, 0.99f})
    cases.push_back(warpCase(WarpType::UniformCone, c, paramText(WarpType::UniformCone, c)));
  for (double s2 : {1e-4, 1e-6}) {
    auto c = static_cast<float>(std::sqrt(1.0 - s2));
    char label[64];
    std::snprintf(label, sizeof label, "%.9g (sin2=%g)", c, s2);
    cases.push_back(warpCase(WarpType::UniformCone, c, label));
  }
  for (float alpha : {0.05f, 0.2f, 0.5f, 1.0f})
    cases.push_back(warpCase(WarpType::Beckmann, alpha, paramText(WarpType::Beckmann, alpha)));
  // The BSDFs: sharp to rough, at normal, oblique and grazing incidence.
  for (const BsdfWarpInputs& in :
       {BsdfWarpInputs{.type = "microfacet", .alpha = 0.05, .kd = 0.3, .incidentDegrees = 30},
        BsdfWarpInputs{.type = "microfacet", .alpha = 0.2, .kd = 0.0, .incidentDegrees = 60},
        BsdfWarpInputs{.type = "microfacet", .alpha = 0.6, .kd = 0.5, .incidentDegrees = 80},
        BsdfWarpInputs{.type = "roughconductor", .alpha = 0.05, .incidentDegrees = 0},
        BsdfWarpInputs{.type = "roughconductor", .alpha = 0.3, .incidentDegrees = 45},
        BsdfWarpInputs{.type = "roughconductor", .alpha = 1.0, .incidentDegrees = 85},
        BsdfWarpInputs{.type = "roughconductor", .distribution = "ggx", .alpha = 0.05, .incidentDegrees = 30},
        BsdfWarpInputs{.type = "roughconductor", .distribution = "ggx", .alpha = 0.3, .incidentDegrees = 60},
        BsdfWarpInputs{.type = "roughconductor", .distribution = "ggx", .alpha = 1.0, .incidentDegrees = 85}})
    cases.push_back(bsdfCase(checkedBsdfWarp(in)));
  return cases;
}

int runAll(const WarpArgs& a) {
  std::vector<Case> cases = allCases();
  Chi2Options opt = chi2OptionsOf(a);
  opt.testCount = static_cast<int>(cases.size());
  std::printf(
      "chi-square tests: %llu samples each, seed %llu, alpha 0.01 over %d tests (Sidak: %.3g per test)\n\n",
      static_cast<unsigned long long>(a.samples), static_cast<unsigned long long>(a.seed), opt.testCount,
      sidakAlpha(opt.alpha, opt.testCount));
  std::printf("%-20s %-26s %12s %6s %10s  %s\n", "warp", "param", "chi2", "dof", "p-value", "verdict");
  int failures = 0;
  for (const Case& c : cases) {
    opt.rejectedDraws = c.rejectedDraws;
    Chi2Result r = chi2Test(c.domain, c.sample, c.pdf, opt);
    if (!r.accepted) ++failures;
    std::printf("%-20s %-26s %12.2f %6d %10.4f  %s%s%s\n", c.name.c_str(), c.label.c_str(), r.chi2, r.dof,
                r.pValue, chi2Verdict(r), r.message.empty() ? "" : ": ", r.message.c_str());
    std::fflush(stdout);
  }
  std::printf("\n%d of %zu accepted\n", static_cast<int>(cases.size()) - failures, cases.size());
  return failures == 0 ? 0 : 1;
}

}  // namespace

void addWarpCommand(CLI::App& app, int& exitCode, WarpGuiRunner gui) {
  auto args = std::make_shared<WarpArgs>();
  CLI::App* cmd = app.add_subcommand(
      "warp", "Chi-square test a sample warp against its pdf; dump samples; evaluate pdfs");
  cmd->footer(
      "A BSDF's sampling is tested with wo at --incident in the xz-plane; its rejected draws (directions "
      "below the surface) dump as '0 0 0' and are tested as a cell expecting the mass its pdf misses.\n"
      "Exit code of a test: 0 accept; 1 REJECT, or inconclusive (too few samples for the grid: pooling "
      "leaves fewer than two cells); 2 bad arguments.");
  cmd->add_option("type", args->type,
                  "Warp: " + warpTypeList() + "; or a BSDF's sampling: " + bsdfWarpTypeList());
  cmd->add_option("--param", args->param,
                  "uniform-cone: cos(theta_max) in [-1, 1) (default 0.5); beckmann: alpha > 0 (default 0.2); "
                  "microfacet, roughconductor: alpha in [0.001, 1000] (default 0.1)");
  cmd->add_option("--incident", args->bsdf.incidentDegrees,
                  "microfacet, roughconductor: the angle of wo = (sin, 0, cos) to the normal, degrees in "
                  "[0, 89.99]")
      ->capture_default_str();
  cmd->add_option("--kd", args->bsdf.kd, "microfacet: the diffuse reflectance in [0, 1]")
      ->capture_default_str();
  cmd->add_option("--int-ior", args->bsdf.intIOR, "microfacet: the interior index of refraction")
      ->capture_default_str();
  cmd->add_option("--ext-ior", args->bsdf.extIOR, "microfacet: the exterior index of refraction")
      ->capture_default_str();
  cmd->add_option("--distribution", args->bsdf.distribution, "roughconductor: beckmann or ggx")
      ->capture_default_str();
  cmd->add_option("--samples", args->samples, "Number of samples for the test")
      ->capture_default_str()
      ->check(unsignedInteger() & CLI::Range(uint64_t(kMinChi2Samples), uint64_t(kMaxChi2Samples)));
  cmd->add_option("--res", args->res,
                  "Histogram resolution (2-D: res x res; sphere: 2res x res in (phi, cos theta))")
      ->capture_default_str()
      ->check(CLI::Range(kMinChi2Resolution, kMaxChi2Resolution));
  addSeedOption(*cmd, args->seed, "Random seed")->capture_default_str();
  auto* all =
      cmd->add_flag("--all", args->all, "Test every warp (several parameters), Sidak-corrected, as a table");
  auto* dump = cmd->add_option("--dump", args->dump, "Write N warped samples to stdout as 'x y z' lines")
                   ->check(unsignedInteger(1'000'000'000));
  auto* pdf = cmd->add_flag("--pdf", args->pdf, "Read 'x y z' lines from stdin, write the pdf of each");
  auto* pdfOf = cmd->add_option("--pdf-of", args->pdfOf, "Judge the samples by the pdf of another warp TYPE");
  cmd->add_option("--pdf-param", args->pdfParam, "Parameter of the --pdf-of warp")->needs(pdfOf);
  auto* scale = cmd->add_option("--pdf-scale", args->pdfScale, "Multiply the judging pdf by this factor")
                    ->capture_default_str();
  auto* mismatch =
      cmd->add_flag("--mismatch", args->mismatch,
                    "Judge the samples by a deliberately wrong pdf (e.g. cosine vs uniform hemisphere)");
  all->excludes(dump)->excludes(pdf)->excludes(pdfOf)->excludes(mismatch)->excludes(scale);
  dump->excludes(pdf)->excludes(pdfOf)->excludes(mismatch)->excludes(scale);
  pdf->excludes(pdfOf)->excludes(mismatch)->excludes(scale);
  mismatch->excludes(pdfOf);

  // The warp inspector (a window of the viewer; offscreen with --offscreen or without a display).
  auto* guiFlag = cmd->add_flag(
      "--gui", args->gui, "Open the warp inspector: points, histogram vs density and the chi-square verdict");
  cmd->add_option("--points", args->points,
                  "--gui: number of points as a power of two, 2^K (K " + std::to_string(kMinLog2Points) +
                      " to " + std::to_string(kMaxLog2Points) + ")")
      ->capture_default_str();
  cmd->add_option("--point-set", args->pointSet,
                  "--gui: independent, grid, stratified or sampler (the first 2^K samples of --sampler's "
                  "--request at --pixel)")
      ->capture_default_str();
  cmd->add_option("--sampler", args->view.sampler, "--gui --point-set sampler: the render sampler")
      ->capture_default_str();
  cmd->add_option("--request", args->view.request,
                  "--gui --point-set sampler: which 2-D request (0: the pixel filter's, 1: the first "
                  "light or direction pair)")
      ->capture_default_str();
  cmd->add_option("--pixel", args->pixel, "--gui --point-set sampler: the pixel, X,Y")->capture_default_str();
  cmd->add_flag("--grid-lines", args->gridLines, "--gui: draw the warped grid lines");
  cmd->add_flag("--offscreen", args->view.offscreen, "--gui: render offscreen (OSMesa) instead of a window");
  cmd->add_option("--screenshot", args->view.screenshot, "--gui: write the last frame to this PNG");
  cmd->add_option("--frames", args->view.frames, "--gui: stop after N frames (offscreen default: 3)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--window", args->view.window, "--gui: window size, e.g. 1280x800");
  cmd->add_flag("--no-wait", args->view.noWait, "--gui offscreen: do not wait for the chi-square test");
  cmd->add_flag("--print-layout", args->view.printLayout, "Print the panels' rectangles (tests)")->group("");
  guiFlag->excludes(all)->excludes(dump)->excludes(pdf)->excludes(pdfOf)->excludes(scale);

  cmd->callback([args, cmd, gui, &exitCode]() {
    const WarpArgs& a = *args;
    if (a.gui) {
      if (!gui) throw Error("--gui: the warp inspector is not part of this build");
      WarpGuiArgs g = a.view;
      if (isBsdfWarpName(a.type)) {
        bsdfWarpOf(a, *cmd);  // checks the values as the test does
        g.bsdf = a.bsdf;
        g.bsdf->type = a.type;
        if (cmd->count("--param")) g.bsdf->alpha = a.param;
      } else {
        g.type = a.type.empty() ? WarpType::CosineHemisphere : parseWarpTypeOrThrow(a.type);
        g.param = checkedWarpParam(g.type, cmd->count("--param") > 0, a.param, "--param");
      }
      g.log2Points = checkedLog2Points(a.points, "--points");
      g.request = checkedSamplerRequest(a.view.request, "--request");
      g.pointSet = a.pointSet;
      g.mismatch = a.mismatch;
      g.gridLines = a.gridLines;
      g.seed = a.seed;
      g.res = cmd->count("--res") ? a.res : 0;
      long long x = 0, y = 0;
      char rest = 0;
      if (std::sscanf(a.pixel.c_str(), "%lld,%lld%c", &x, &y, &rest) != 2)
        throw Error("--pixel " + a.pixel + ": expected X,Y, e.g. 3,5");
      const IVec2 pixel = checkedSamplerPixel(x, y, "--pixel");
      g.pixelX = pixel.x, g.pixelY = pixel.y;
      exitCode = gui(g);
      return;
    }
    for (const char* o : {"--points", "--point-set", "--sampler", "--request", "--pixel", "--grid-lines",
                          "--offscreen", "--screenshot", "--frames", "--window", "--no-wait"})
      if (cmd->count(o)) throw Error(std::string(o) + " is an option of the warp inspector: add --gui");
    if (a.all) {
      for (const char* o : {"--param", "--incident", "--kd", "--int-ior", "--ext-ior", "--distribution"})
        if (cmd->count(o)) throw Error(std::string("--all runs every warp: give no TYPE or ") + o);
      if (!a.type.empty()) throw Error("--all runs every warp: give no TYPE or --param");
      exitCode = runAll(a);
      return;
    }
    if (a.type.empty()) throw Error("missing warp TYPE (one of: " + warpTypeList() + "), or use --all");
    if (!(a.pdfScale > 0.0 && std::isfinite(a.pdfScale)))
      throw Error("--pdf-scale must be a positive number");
    if (isBsdfWarpName(a.type)) {
      const BsdfWarp warp = bsdfWarpOf(a, *cmd);
      if (a.pdf)
        evaluatePdfs(bsdfPdfFunction(warp));
      else if (cmd->count("--dump"))
        dumpSamples(bsdfSampleFunction(warp), a.dump, a.seed);
      exitCode = a.pdf || cmd->count("--dump") ? 0 : runBsdfSingle(a, *cmd);
      return;
    }
    for (const char* o : {"--incident", "--kd", "--int-ior", "--ext-ior", "--distribution"})
      if (cmd->count(o))
        throw Error(std::string(o) + " is a parameter of the BSDFs (" + bsdfWarpTypeList() + ")");
    if (cmd->count("--dump") || a.pdf) {
      WarpType type = parseWarpTypeOrThrow(a.type);
      float param = checkedWarpParam(type, cmd->count("--param") > 0, a.param, "--param");
      if (a.pdf)
        evaluatePdfs(warpPdfFunction(type, param));
      else
        dumpSamples(warpSampleFunction(type, param), a.dump, a.seed);
      exitCode = 0;
      return;
    }
    exitCode = runSingle(a, *cmd);
  });
}

}  // namespace penumbra::cli
