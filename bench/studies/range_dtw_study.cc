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
#include <sstream>
#include <string>
#include <vector>

#include "bench/studies/study_archive.h"
#include "engine/cluster/warped_similarity.h"

namespace {

struct Range {
  std::string label;
  uint64_t start = 0;
  uint64_t end = 0;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: range_dtw_study ARCHIVE.mfs RANGES.tsv\n";
    return 2;
  }
  auto archive = motif::testing::OpenStudyArchive(argv[1]);
  if (!archive.ok()) {
    std::cerr << archive.status().ToString() << "\n";
    return 1;
  }
  const motif::PoseFeatures& features = archive->features;
  std::vector<Range> ranges;
  std::ifstream in(argv[2]);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Range range;
    std::getline(fields, range.label, '\t');
    fields >> range.start >> range.end;
    if (!fields || range.end <= range.start || range.end > features.frame_count()) {
      std::cerr << "skipped: " << line << "\n";
      continue;
    }
    ranges.push_back(range);
  }
  for (const Range& a : ranges) {
    std::printf("%-28s [%5llu,%5llu)", a.label.c_str(), static_cast<unsigned long long>(a.start),
                static_cast<unsigned long long>(a.end));
    for (const Range& b : ranges)
      std::printf(" %5.3f", motif::MeanWarpedDistance(features, a.start, a.end, b.start, b.end));
    std::printf("\n");
  }
  return 0;
}
