#include "app/mpi/rank_agreement.h"

#include <algorithm>
#include <cstdio>
#include <utility>
#include <vector>

namespace penumbra::mpi {

namespace {

// "rank 3" or "ranks 0-2, 5" for ascending ranks.
std::string rankList(const std::vector<int>& ranks) {
  std::string out = ranks.size() == 1 ? "rank " : "ranks ";
  for (size_t i = 0; i < ranks.size();) {
    size_t last = i;
    while (last + 1 < ranks.size() && ranks[last + 1] == ranks[last] + 1) ++last;
    out += (i ? ", " : "") + std::to_string(ranks[i]) + (last > i ? "-" + std::to_string(ranks[last]) : "");
    i = last + 1;
  }
  return out;
}

void printRemovingTrailingNewline(const std::string& head, std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  std::fprintf(stderr, "%s%s\n", head.c_str(), text.c_str());
}

constexpr size_t kMostDifferencesShown = 8;  // distinct differences printed; the rest are counted

// Each distinct non-empty text once, with the ascending ranks that gave it, in the order of the
// first such rank.
std::vector<std::pair<std::string, std::vector<int>>> groupedByText(const std::vector<std::string>& texts) {
  std::vector<std::pair<std::string, std::vector<int>>> groups;
  for (int r = 0; r < int(texts.size()); ++r) {
    const std::string& text = texts[size_t(r)];
    if (text.empty()) continue;
    size_t g = 0;
    while (g < groups.size() && groups[g].first != text) ++g;
    if (g == groups.size()) groups.push_back({text, {}});
    groups[g].second.push_back(r);
  }
  return groups;
}

}  // namespace

bool everyRankSucceeded(const Session& session, const std::string& failure) {
  if (session.sumOf(failure.empty() ? 0 : 1) == 0) return true;
  const std::vector<std::string> failures = session.gatherToRoot(failure);
  if (session.rank() != 0) return false;
  std::vector<int> failed;
  for (const auto& [message, ranks] : groupedByText(failures)) {
    printRemovingTrailingNewline(
        "error (" + rankList(ranks) + " of " + std::to_string(session.size()) + "): ", message);
    failed.insert(failed.end(), ranks.begin(), ranks.end());
  }
  std::sort(failed.begin(), failed.end());
  std::fprintf(stderr, "error: %s failed before the render; no rank rendered and nothing was written\n",
               rankList(failed).c_str());
  std::fflush(stderr);
  return false;
}

bool everyRankAgrees(const Session& session, const RunDescription& description) {
  const std::vector<uint64_t> digests = session.allGather(digestOf(description));
  bool same = true;
  for (uint64_t d : digests) same = same && d == digests[0];
  if (same) return true;
  // Rare and small: rank 0's whole description to every rank, and each rank's first difference back.
  const RunDescription root = deserialize(session.broadcastFromRoot(serialize(description)));
  std::string difference;
  if (digests[size_t(session.rank())] != digests[0]) {
    difference = firstDifference(description, root);
    if (difference.empty()) difference = ": the same settings in another order (a different penumbra-mpi?)";
  }
  const std::vector<std::string> differences = session.gatherToRoot(difference);
  if (session.rank() != 0) return false;
  const auto groups = groupedByText(differences);
  for (size_t g = 0; g < groups.size() && g < kMostDifferencesShown; ++g) {
    const std::vector<int>& ranks = groups[g].second;
    std::fprintf(stderr, "error: %s %s with rank 0%s\n", rankList(ranks).c_str(),
                 ranks.size() == 1 ? "disagrees" : "disagree", groups[g].first.c_str());
  }
  if (groups.size() > kMostDifferencesShown)
    std::fprintf(stderr, "error: and %zu other differences\n", groups.size() - kMostDifferencesShown);
  std::fprintf(stderr,
               "error: every rank must render the same scene with the same settings; nothing was rendered or "
               "written\n");
  std::fflush(stderr);
  return false;
}

}  // namespace penumbra::mpi
