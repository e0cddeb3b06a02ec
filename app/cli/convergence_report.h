// Files written by `penumbra converge`: convergence.csv, convergence.png (Cairo),
// equal-time.png (Cairo) and summary.md. Plotting lives in app/, never in core/.
#pragma once

#include <string>
#include <vector>

#include "core/analysis/convergence.h"

namespace penumbra::cli {

struct ReportInfo {
  std::string sceneName;
  std::string referenceSource;
  bool sppMode = false;  // x axis: spp instead of seconds
  bool cpuAxis = false;  // x axis: the render's CPU seconds instead of wall seconds
  double budget = 0;     // seconds (or spp) per strategy
  int threads = 0;
  int width = 0, height = 0;
  std::size_t noLightPixels = 0, pixels = 0;
};

void writeConvergenceCsv(const std::string& path, const std::vector<ConvergenceRun>& runs);
void plotConvergence(const std::string& path, const std::vector<ConvergenceRun>& runs,
                     const ReportInfo& info);
void writeEqualTimeImage(const std::string& path, const std::vector<ConvergenceRun>& runs,
                         const Reference& ref, const ReportInfo& info);
void writeSummary(const std::string& path, const std::vector<ConvergenceRun>& runs, const ReportInfo& info);

}  // namespace penumbra::cli
