// Study: how far apart, in time-warped pose distance, are frame ranges of one archive? Prints
// the mean pose distance along the DTW path between every pair of the given ranges, so one can
// see whether repetitions of one movement are closer to each other than to other movements
// (docs/design/motif_quality.md).
//
//   range_dtw_study ARCHIVE.mfs RANGES.tsv
// RANGES.tsv: lines "label<TAB>start<TAB>end" in global frames (end exclusive); '#' comments.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "engine/distance/pose_features.h"
#include "formats/frame_file/frame_file_reader.h"

namespace {

struct Range {
  std::string label;
  uint64_t start = 0;
  uint64_t end = 0;
};

// Mean pose distance along the cheapest warping path (steps (1,0), (0,1), (1,1)).
double MeanDtw(const motif::PoseFeatures& features, const Range& a, const Range& b) {
  const uint64_t n = a.end - a.start;
  const uint64_t m = b.end - b.start;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> cost((n + 1) * (m + 1), inf);
  std::vector<uint32_t> steps((n + 1) * (m + 1), 0);
  auto at = [&](uint64_t i, uint64_t j) { return i * (m + 1) + j; };
  cost[at(0, 0)] = 0;
  for (uint64_t i = 1; i <= n; ++i) {
    for (uint64_t j = 1; j <= m; ++j) {
      const double d = motif::PoseDistance(features, a.start + i - 1, b.start + j - 1);
      uint64_t best = at(i - 1, j - 1);
      if (cost[at(i - 1, j)] < cost[best]) best = at(i - 1, j);
      if (cost[at(i, j - 1)] < cost[best]) best = at(i, j - 1);
      cost[at(i, j)] = cost[best] + d;
      steps[at(i, j)] = steps[best] + 1;
    }
  }
  return cost[at(n, m)] / steps[at(n, m)];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: range_dtw_study ARCHIVE.mfs RANGES.tsv\n";
    return 2;
  }
  auto reader = motif::FrameFileReader::Open(argv[1]);
  if (!reader.ok()) {
    std::cerr << reader.status().ToString() << "\n";
    return 1;
  }
  auto weights = motif::LoadDistanceWeights((*reader)->skeleton(), "");
  if (!weights.ok()) {
    std::cerr << weights.status().ToString() << "\n";
    return 1;
  }
  auto features = motif::PoseFeatures::FromArchive(**reader, *weights);
  if (!features.ok()) {
    std::cerr << features.status().ToString() << "\n";
    return 1;
  }
  std::vector<Range> ranges;
  std::ifstream in(argv[2]);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Range range;
    std::getline(fields, range.label, '\t');
    fields >> range.start >> range.end;
    if (!fields || range.end <= range.start || range.end > features->frame_count()) {
      std::cerr << "skipped: " << line << "\n";
      continue;
    }
    ranges.push_back(range);
  }
  for (const Range& a : ranges) {
    std::printf("%-28s [%5llu,%5llu)", a.label.c_str(), static_cast<unsigned long long>(a.start),
                static_cast<unsigned long long>(a.end));
    for (const Range& b : ranges) std::printf(" %5.3f", MeanDtw(*features, a, b));
    std::printf("\n");
  }
  return 0;
}
