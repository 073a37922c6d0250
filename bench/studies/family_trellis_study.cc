// Study: path families (thumbnail_study's choice, docs/design/motif_quality.md, sections 10 and
// 11) on the miner's own trellis and paths, as a miner at scale would find them: no dense matrix.
//
//   family_trellis_study ARCHIVE.mfs TRELLIS.mtr PATHS.mpa [rho=0.1] [cap_degrees=16]
//                        [samples=64] [exclusion=0.25] [min_seconds=0.6] [motifs=20]
//                        [overlap=0.25] [pauses=1] [gap_seconds=0.25] [penalty=-2]
// Prints families in thumbnail_study's format: "fitness score coverage start end" (the segment),
// then "start end" of each of its segments (archive frames, end exclusive), best first.
//
// Each frame f gets a threshold t(f): the rho-quantile of its distances to about `samples`
// frames of its own clip at least `exclusion` seconds away (evenly spaced), at most the
// joint-angle radius of cap_degrees. A trellis node (column j, frame i, distance d) is similar
// when d <= min(t(i), t(j)) and neither frame is in a pause; it scores 1 - d / 2 min(t). The
// segments tried: both segments of each path, from min_seconds on. A segment S = [a, a + L)
// gets its family in one streaming pass over the trellis's columns, all segments at once: a
// path runs through similar nodes whose frames are S's rows a, a + 1, ... a + L - 1 in order,
// with steps of up to gap_seconds in rows and columns (slope at most 2; each skipped diagonal
// cell, and each row missed at either end, costs `penalty`: a path crosses dissimilar cells as in
// the dense matrix, but only up to the next similar node); a family is paths one after
// the other in columns, none in S's own columns, with the highest total. Fitness as in
// thumbnail_study: the harmonic mean of score = total / (covered + L) and coverage = covered /
// frames. Families are taken by fitness while none of their segments shares more than `overlap`
// of the shorter with a segment taken before. Cost: O(frames x samples) distances, and
// O(nodes x segments a frame x gap^2) for the pass (a study: a miner would keep each row's best
// recent totals instead of looking back gap^2 cells).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "bench/studies/experiment_args.h"
#include "bench/studies/study_archive.h"
#include "engine/cluster/pauses.h"
#include "engine/distance/pose_features.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/paths_file/paths_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace {

using motif::testing::ExperimentArgs;

// Each frame's threshold: the rho-quantile of its distances to sampled frames of its clip.
std::vector<float> FrameThresholds(const motif::PoseFeatures& features,
                                   const motif::FrameFileReader& archive, double rho, int samples,
                                   uint64_t exclusion, float cap) {
  std::vector<float> thresholds(features.frame_count(), cap);
  std::vector<float> row;
  for (const motif::ClipInfo& clip : archive.clips()) {
    const uint64_t stride = std::max<uint64_t>(1, clip.frame_count / samples);
    for (uint64_t f = clip.first_frame; f < clip.first_frame + clip.frame_count; ++f) {
      row.clear();
      for (uint64_t g = clip.first_frame + (f * 7) % stride;  // rows see staggered columns
           g < clip.first_frame + clip.frame_count; g += stride) {
        if (g + exclusion <= f || f + exclusion <= g)
          row.push_back(motif::PoseDistance(features, f, g));
      }
      if (row.empty()) continue;
      const auto q =
          std::min(row.size() - 1, static_cast<size_t>(rho * static_cast<double>(row.size())));
      std::nth_element(row.begin(), row.begin() + static_cast<long>(q), row.end());
      thresholds[f] = std::max(1e-6f, std::min(cap, row[q]));
    }
  }
  return thresholds;
}

struct Segment {
  uint64_t start = 0, length = 0;
};

struct Completion {  // a path from S's first row to its last
  uint64_t first_column = 0, last_column = 0;
  double total = 0;     // of the family ending with this path
  int64_t before = -1;  // the completion ending the family before it, or -1
};

// One segment's family search state: a ring of gap + 1 columns' best totals per row.
struct FamilySearch {
  Segment segment;
  int gap = 1;
  double penalty = -2;
  std::vector<std::vector<double>> value;
  std::vector<std::vector<uint64_t>> first, stamp;
  std::vector<std::vector<int64_t>> before;
  std::vector<Completion> completions;
  double elevator = 0;  // the best family ending before the current column
  int64_t elevator_end = -1;
  double pending = 0;  // completions of the current column, for the next ones
  int64_t pending_end = -1;

  FamilySearch(Segment s, int g, double p) : segment(s), gap(g), penalty(p) {
    const auto slots = static_cast<size_t>(gap + 1);
    value.assign(slots, std::vector<double>(s.length, 0));
    first.assign(slots, std::vector<uint64_t>(s.length, 0));
    stamp.assign(slots, std::vector<uint64_t>(s.length, std::numeric_limits<uint64_t>::max()));
    before.assign(slots, std::vector<int64_t>(s.length, -1));
  }

  // Column j has a similar node at S's row `row` scoring `sim`. A path reaches it from a node
  // up to `gap` rows and columns back (slope at most 2), each skipped diagonal cell costing
  // `penalty`, or starts there (the rows before it costing `penalty` each). True when a path
  // through it completes a better family (EndColumn must follow the column).
  bool Visit(uint64_t j, uint64_t row, double sim) {
    const auto slots = static_cast<uint64_t>(gap + 1);
    bool found = false;
    double best = 0;
    uint64_t from_first = j;
    int64_t from_before = elevator_end;
    if (row < static_cast<uint64_t>(gap)) {
      found = true;
      best = elevator + penalty * static_cast<double>(row);
    }
    for (uint64_t dc = 1; dc <= static_cast<uint64_t>(gap) && dc <= j; ++dc) {
      for (uint64_t dr = 1; dr <= static_cast<uint64_t>(gap) && dr <= row; ++dr) {
        if (std::max(dr, dc) > 2 * std::min(dr, dc)) continue;
        const uint64_t column = j - dc;
        const uint64_t s = column % slots;
        if (stamp[s][row - dr] != column) continue;
        const double total =
            value[s][row - dr] + penalty * static_cast<double>(std::min(dr, dc) - 1);
        if (found && total <= best) continue;
        found = true;
        best = total;
        from_first = first[s][row - dr];
        from_before = before[s][row - dr];
      }
    }
    if (!found) return false;
    const uint64_t slot = j % slots;
    const double total = best + sim;
    if (stamp[slot][row] == j && value[slot][row] >= total) return false;
    value[slot][row] = total;
    first[slot][row] = from_first;
    before[slot][row] = from_before;
    stamp[slot][row] = j;
    const uint64_t left = segment.length - 1 - row;
    const double complete = total + penalty * static_cast<double>(left);
    if (left < static_cast<uint64_t>(gap) && complete > pending) {
      completions.push_back({from_first, j, complete, from_before});
      pending = complete;
      pending_end = static_cast<int64_t>(completions.size() - 1);
      return true;
    }
    return false;
  }

  void EndColumn() {
    if (pending > elevator) {
      elevator = pending;
      elevator_end = pending_end;
    }
  }

  std::vector<std::pair<uint64_t, uint64_t>> Paths() const {
    std::vector<std::pair<uint64_t, uint64_t>> paths;
    for (int64_t at = elevator_end; at >= 0; at = completions[at].before) {
      paths.push_back({completions[at].first_column, completions[at].last_column + 1});
    }
    std::reverse(paths.begin(), paths.end());
    return paths;
  }
};

struct Family {
  double fitness = 0, score = 0, coverage = 0;
  Segment segment;
  std::vector<std::pair<uint64_t, uint64_t>> segments;  // with the segment itself, by start
};

std::vector<Segment> CandidateSegments(const motif::PathsFileReader& paths, uint64_t min_length,
                                       const motif::FrameFileReader& archive) {
  std::vector<Segment> segments;
  for (const motif::PathCandidate& path : paths.candidates()) {
    for (auto [a, b] :
         {std::pair{path.top_start, path.top_end}, std::pair{path.match_start, path.match_end}}) {
      if (b - a < min_length || archive.ClipOfFrame(a) != archive.ClipOfFrame(b - 1)) continue;
      segments.push_back({a, b - a});
    }
  }
  std::sort(segments.begin(), segments.end(), [](const Segment& x, const Segment& y) {
    return std::pair{x.start, x.length} < std::pair{y.start, y.length};
  });
  segments.erase(std::unique(segments.begin(), segments.end(),
                             [](const Segment& x, const Segment& y) {
                               return x.start == y.start && x.length == y.length;
                             }),
                 segments.end());
  return segments;
}

// Frames inside a pause of the archive (engine/cluster/pauses.h).
motif::Result<std::vector<char>> StillFrames(const motif::FrameFileReader& archive) {
  MOTIF_ASSIGN_OR_RETURN(const std::vector<motif::MotifInstance> pauses,
                         motif::FindPauses(archive, motif::PauseOptions{}));
  std::vector<char> still(archive.frame_count(), 0);
  for (const auto& pause : pauses) {
    std::fill(still.begin() + static_cast<long>(pause.start),
              still.begin() + static_cast<long>(pause.end), 1);
  }
  return still;
}

// The streaming pass: every segment's family search, fed the similar nodes of each trellis
// column whose frame is one of its rows.
motif::Result<std::vector<FamilySearch>> SearchFamilies(const motif::TrellisFileReader& trellis,
                                                        const std::vector<Segment>& segments,
                                                        const std::vector<float>& thresholds,
                                                        const std::vector<char>& still, int gap,
                                                        double penalty) {
  std::vector<FamilySearch> searches;
  searches.reserve(segments.size());
  for (const Segment& segment : segments) searches.emplace_back(segment, gap, penalty);
  std::vector<std::vector<uint32_t>> rows_of(thresholds.size());  // the searches a frame is in
  for (uint32_t idx = 0; idx < segments.size(); ++idx) {
    for (uint64_t f = segments[idx].start; f < segments[idx].start + segments[idx].length; ++f) {
      rows_of[f].push_back(idx);
    }
  }
  motif::TrellisBlock block;
  std::vector<uint32_t> completed;  // searches with a completion in the current column
  for (uint64_t block_idx = 0; block_idx < trellis.block_count(); ++block_idx) {
    MOTIF_RETURN_IF_ERROR(trellis.ReadBlock(block_idx, &block));
    for (uint32_t c = 0; c < block.column_count; ++c) {
      const uint64_t j = block.first_column + c;
      for (uint32_t at = block.offsets[c]; at < block.offsets[c + 1]; ++at) {
        const motif::Neighbour& node = block.neighbours[at];
        const uint64_t i = node.frame;
        if (rows_of[i].empty() || still[i] || still[j]) continue;
        const float t = std::min(thresholds[i], thresholds[j]);
        if (node.distance > t) continue;
        const double sim = 1.0 - 0.5 * node.distance / t;
        for (uint32_t idx : rows_of[i]) {
          const Segment& s = segments[idx];
          if (j >= s.start && j < s.start + s.length) continue;  // its own columns
          if (searches[idx].Visit(j, i - s.start, sim)) completed.push_back(idx);
        }
      }
      for (uint32_t idx : completed) searches[idx].EndColumn();
      completed.clear();
    }
  }
  return searches;
}

// The searches' families (each with its segment), best fitness first.
std::vector<Family> RankedFamilies(const std::vector<FamilySearch>& searches, uint64_t frames) {
  std::vector<Family> families;
  for (const FamilySearch& search : searches) {
    Family family;
    family.segment = search.segment;
    family.segments = search.Paths();
    if (family.segments.empty()) continue;
    uint64_t covered = 0;
    for (auto [a, b] : family.segments) covered += b - a;
    family.score = search.elevator / static_cast<double>(covered + search.segment.length);
    family.coverage = static_cast<double>(covered) / static_cast<double>(frames);
    family.fitness = 2 * family.score * family.coverage / (family.score + family.coverage);
    family.segments.push_back({search.segment.start, search.segment.start + search.segment.length});
    std::sort(family.segments.begin(), family.segments.end());
    families.push_back(std::move(family));
  }
  std::sort(families.begin(), families.end(),
            [](const Family& x, const Family& y) { return x.fitness > y.fitness; });
  return families;
}

// Prints up to `motifs` families in order, skipping one with a segment that shares more than
// `overlap` of the shorter with a segment printed before.
void PrintFamilies(const std::vector<Family>& families, double overlap, int motifs) {
  std::vector<std::pair<uint64_t, uint64_t>> taken;
  int printed = 0;
  for (const Family& family : families) {
    if (printed >= motifs) break;
    bool clash = false;
    for (auto [a, b] : family.segments) {
      for (auto [c, d] : taken) {
        const uint64_t shared =
            std::min(b, d) > std::max(a, c) ? std::min(b, d) - std::max(a, c) : 0;
        clash = clash ||
                static_cast<double>(shared) > overlap * static_cast<double>(std::min(b - a, d - c));
      }
    }
    if (clash) continue;
    std::printf("%.4f %.4f %.4f %llu %llu\n", family.fitness, family.score, family.coverage,
                static_cast<unsigned long long>(family.segment.start),
                static_cast<unsigned long long>(family.segment.start + family.segment.length));
    for (auto [a, b] : family.segments) {
      std::printf("%llu %llu\n", static_cast<unsigned long long>(a),
                  static_cast<unsigned long long>(b));
      taken.push_back({a, b});
    }
    ++printed;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr << "usage: family_trellis_study ARCHIVE.mfs TRELLIS.mtr PATHS.mpa [rho=0.1] "
                 "[cap_degrees=16] [samples=64] [exclusion=0.25] [min_seconds=0.6] [motifs=20] "
                 "[overlap=0.25] [pauses=1] [gap_seconds=0.25] [penalty=-2]\n";
    return 2;
  }
  const ExperimentArgs args(argc - 3, argv + 3);
  auto archive = motif::testing::OpenStudyArchive(argv[1]);
  auto trellis = motif::TrellisFileReader::Open(argv[2]);
  auto paths = motif::PathsFileReader::Open(argv[3]);
  for (const motif::Status& status : {archive.status(), trellis.status(), paths.status()}) {
    if (!status.ok()) {
      std::cerr << status.ToString() << "\n";
      return 1;
    }
  }
  const motif::FrameFileReader& reader = *archive->reader;
  const motif::PoseFeatures& features = archive->features;
  const double fps = reader.fps();
  const float weight_sum =
      std::accumulate(features.weights().begin(), features.weights().end(), 0.0f);
  const float cap =
      static_cast<float>(weight_sum * 2 * std::sin(args.number("cap_degrees", 16) * M_PI / 720));
  const auto exclusion = static_cast<uint64_t>(std::lround(args.number("exclusion", 0.25) * fps));
  const std::vector<float> thresholds =
      FrameThresholds(features, reader, args.number("rho", 0.1),
                      static_cast<int>(args.number("samples", 64)), exclusion, cap);
  auto still = args.number("pauses", 1) != 0
                   ? StillFrames(reader)
                   : motif::Result<std::vector<char>>(std::vector<char>(features.frame_count(), 0));
  const auto min_length = static_cast<uint64_t>(std::lround(args.number("min_seconds", 0.6) * fps));
  const int gap =
      std::max(1, static_cast<int>(std::lround(args.number("gap_seconds", 0.25) * fps)));
  auto searches = still.ok()
                      ? SearchFamilies(**trellis, CandidateSegments(**paths, min_length, reader),
                                       thresholds, *still, gap, args.number("penalty", -2))
                      : motif::Result<std::vector<FamilySearch>>(still.status());
  if (!searches.ok()) {
    std::cerr << searches.status().ToString() << "\n";
    return 1;
  }
  PrintFamilies(RankedFamilies(*searches, features.frame_count()), args.number("overlap", 0.25),
                static_cast<int>(args.number("motifs", 20)));
  return 0;
}
