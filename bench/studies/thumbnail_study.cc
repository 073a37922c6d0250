// Study: the "thumbnail" of one take (after Müller's audio thumbnailing, Müller, Jiang & Grosche
// 2013): the segment whose best path family in the take's self-similarity matrix explains the
// most of the take, and the segments that family induces, its repetitions. A prototype of
// another way to choose a take's first motif, measured against `motifmine mine` in
// docs/design/motif_quality.md, section 10. Dense: O(n^2) memory and O(n^3) time in the sampled
// frames n, so for single takes and small folders only.
//
//   thumbnail_study ARCHIVE.mfs [step=4] [rho=0.1] [cap_degrees=16] [penalty=-2]
//                   [exclusion=0.25] [min_seconds=0.6] [smooth=1] [pauses=1] [neighbours=0]
//                   [per_clip=0]
// Prints "fitness score coverage start end" of the thumbnail, then "start end" of every
// segment its family induces (archive frames, end exclusive). The archive's clips are taken as
// one sequence (a path may cross from one clip into the next).
//
// The matrix: the pose distance between every pair of sampled frames (every `step`-th), with
// paths enhanced (the mean along the diagonal over +-0.25 s, the least over tempi 0.66-1.5).
// Row i's threshold is the rho-quantile of its distances to frames at least `exclusion` seconds
// away (with neighbours = K > 0: its distance to the K-th nearest such frame, K counted in
// archive frames, as a trellis with k_max = K keeps them; with per_clip=1 only the row's own
// clip's frames count), capped at the joint-angle radius of
// `cap_degrees` (0: no cap); a pair under the smaller threshold of its two rows scores 1 - d / 2t
// (in [0.5, 1]), any other `penalty`, and a frame in a pause (engine/cluster/pauses.h) only
// `penalty`. The family of a segment: the non-overlapping paths (steps (1,1), (2,1), (1,2)) through
// its rows with the highest total. Fitness: the harmonic mean of its normalised score and coverage,
// the segment's own path left out; segments from min_seconds to half the take.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <utility>
#include <vector>

#include "bench/studies/experiment_args.h"
#include "engine/cluster/pauses.h"
#include "engine/distance/pose_features.h"
#include "formats/frame_file/frame_file_reader.h"

namespace {

struct SquareMatrix {
  int n = 0;
  std::vector<float> values;
  explicit SquareMatrix(int size) : n(size), values(static_cast<size_t>(size) * size) {}
  float& at(int i, int j) { return values[static_cast<size_t>(i) * n + j]; }
  float at(int i, int j) const { return values[static_cast<size_t>(i) * n + j]; }
};

struct Family {
  double score = 0;
  std::vector<std::pair<int, int>> segments;  // sampled frames, end exclusive
};

// D is symmetric: each pair is measured once.
SquareMatrix Distances(const motif::PoseFeatures& features, int n, int step) {
  SquareMatrix dist(n);
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      dist.at(i, j) = dist.at(j, i) = motif::PoseDistance(features, static_cast<uint64_t>(i) * step,
                                                          static_cast<uint64_t>(j) * step);
    }
  }
  return dist;
}

// The mean distance along the diagonal through (i, j) over +-half samples, the least over tempi.
SquareMatrix EnhancePaths(const SquareMatrix& dist, int half) {
  const double tempi[] = {0.66, 0.8, 1.0, 1.25, 1.5};
  SquareMatrix smooth(dist.n);
  for (int i = 0; i < dist.n; ++i) {
    for (int j = 0; j < dist.n; ++j) {
      float best = 1e30f;
      for (double tempo : tempi) {
        double sum = 0;
        int count = 0;
        for (int k = -half; k <= half; ++k) {
          const int a = i + k;
          const int b = j + static_cast<int>(std::lround(k * tempo));
          if (a < 0 || a >= dist.n || b < 0 || b >= dist.n) continue;
          sum += dist.at(a, b);
          ++count;
        }
        if (count > 0) best = std::min(best, static_cast<float>(sum / count));
      }
      smooth.at(i, j) = best;
    }
  }
  return smooth;
}

// Each row's threshold: the rho-quantile of its distances to frames `exclusion` or more away
// (or, with neighbours > 0, its neighbours-th smallest, as a trellis keeps k_max), at most `cap`.
// With `clip_of` (each sampled frame's clip), only frames of the row's own clip count.
std::vector<float> RowThresholds(const SquareMatrix& smooth, double rho, int neighbours,
                                 int exclusion, float cap, const std::vector<int>& clip_of) {
  std::vector<float> thresholds(smooth.n);
  for (int i = 0; i < smooth.n; ++i) {
    std::vector<float> row;
    for (int j = 0; j < smooth.n; ++j) {
      if (!clip_of.empty() && clip_of[i] != clip_of[j]) continue;
      if (std::abs(i - j) >= exclusion) row.push_back(smooth.at(i, j));
    }
    if (row.empty()) row.push_back(cap);
    const size_t rank = neighbours > 0 ? static_cast<size_t>(neighbours)
                                       : static_cast<size_t>(rho * static_cast<double>(row.size()));
    const size_t q = std::min(row.size() - 1, rank);
    std::nth_element(row.begin(), row.begin() + static_cast<long>(q), row.end());
    thresholds[i] = std::max(std::min(row[q], cap), 1e-6f);
  }
  return thresholds;
}

// Frames (sampled) inside a pause of the archive.
motif::Result<std::vector<char>> StillFrames(const motif::FrameFileReader& reader, int n,
                                             int step) {
  MOTIF_ASSIGN_OR_RETURN(const std::vector<motif::MotifInstance> pauses,
                         motif::FindPauses(reader, motif::PauseOptions{}));
  std::vector<char> still(n, 0);
  for (const auto& pause : pauses) {
    for (uint64_t frame = pause.start; frame < pause.end; ++frame) {
      if (frame / step < static_cast<uint64_t>(n)) still[frame / step] = 1;
    }
  }
  return still;
}

SquareMatrix Similarity(const SquareMatrix& smooth, const std::vector<float>& thresholds,
                        const std::vector<char>& still, float penalty) {
  SquareMatrix sim(smooth.n);
  for (int i = 0; i < smooth.n; ++i) {
    for (int j = 0; j < smooth.n; ++j) {
      const float threshold = std::min(thresholds[i], thresholds[j]);
      const float d = smooth.at(i, j);
      const bool similar = d <= threshold && !still[i] && !still[j];
      sim.at(i, j) = similar ? 1.0f - 0.5f * d / threshold : penalty;
    }
    sim.at(i, i) = 1.0f;
  }
  return sim;
}

// The best path family through rows [s, s + len): D(l, c) the best total of a family whose
// last path is at (l, c); the elevator E(c) the best total of a family ended before column c.
Family BestFamily(const SquareMatrix& sim, int s, int len) {
  const int n = sim.n;
  const float kNone = -1e30f;
  std::vector<float> total(static_cast<size_t>(len) * n, kNone);
  std::vector<int> start(total.size(), -1);
  std::vector<float> elevator(n, 0);
  std::vector<int> ended(n, -1);  // elevator(c) came from a path ending at ended[c], or -1
  auto at = [n](int l, int c) { return static_cast<size_t>(l) * n + c; };
  for (int c = 0; c < n; ++c) {
    if (c > 0) {
      elevator[c] = elevator[c - 1];
      if (total[at(len - 1, c - 1)] > elevator[c]) {
        elevator[c] = total[at(len - 1, c - 1)];
        ended[c] = c - 1;
      }
    }
    total[at(0, c)] = elevator[c] + sim.at(s, c);
    start[at(0, c)] = c;
    for (int l = 1; l < len; ++l) {
      size_t from = 0;
      float best = kNone;
      auto consider = [&](int pl, int pc) {
        if (pl >= 0 && pc >= 0 && total[at(pl, pc)] > best)
          best = total[at(pl, pc)], from = at(pl, pc);
      };
      consider(l - 1, c - 1);
      consider(l - 2, c - 1);
      consider(l - 1, c - 2);
      if (best <= kNone / 2) continue;
      total[at(l, c)] = best + sim.at(s + l, c);
      start[at(l, c)] = start[from];
    }
  }
  Family family;
  family.score = elevator[n - 1];
  bool in_path = total[at(len - 1, n - 1)] > family.score;
  if (in_path) family.score = total[at(len - 1, n - 1)];
  int c = n - 1;
  while (c >= 0) {  // back: a path to its first column, then the elevator to the path before
    if (in_path) {
      const int first = start[at(len - 1, c)];
      family.segments.push_back({first, c + 1});
      c = first;
      in_path = false;
    } else if (c == 0) {
      break;
    } else if (ended[c] >= 0) {
      c = ended[c];
      in_path = true;
    } else {
      --c;
    }
  }
  std::reverse(family.segments.begin(), family.segments.end());
  return family;
}

struct Thumbnail {
  double fitness = -1, score = 0, coverage = 0;
  int start = 0, length = 0;
};

Thumbnail FindThumbnail(const SquareMatrix& sim, int min_length) {
  Thumbnail best;
  const int n = sim.n;
  for (int len = min_length; len <= n / 2; len += std::max(1, len / 10)) {
    for (int s = 0; s + len <= n; s += 2) {
      const Family family = BestFamily(sim, s, len);
      if (family.segments.size() < 2) continue;
      int covered = 0;
      for (auto [a, b] : family.segments) covered += b - a;
      const double score = (family.score - len) / std::max(1, covered);
      const double coverage = static_cast<double>(covered - len) / n;
      if (score <= 0 || coverage <= 0) continue;
      const double fitness = 2 * score * coverage / (score + coverage);
      if (fitness > best.fitness) best = {fitness, score, coverage, s, len};
    }
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: thumbnail_study ARCHIVE.mfs [step=4] [rho=0.1] [cap_degrees=16] "
                 "[penalty=-2] [exclusion=0.25] [min_seconds=0.6] [smooth=1] [pauses=1] "
                 "[neighbours=0] [per_clip=0]\n";
    return 2;
  }
  const motif::testing::ExperimentArgs args(argc - 1, argv + 1);
  const int step = std::max(1, static_cast<int>(args.number("step", 4)));
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
  const double per_second = (*reader)->fps() / step;
  const int n = static_cast<int>(features->frame_count() / step);
  const SquareMatrix dist = Distances(*features, n, step);
  const SquareMatrix smooth =
      args.number("smooth", 1) != 0
          ? EnhancePaths(dist, std::max(1, static_cast<int>(std::lround(0.25 * per_second))))
          : dist;
  double weight_sum = 0;
  for (float weight : features->weights()) weight_sum += weight;
  const double cap_degrees = args.number("cap_degrees", 16);
  const float cap = cap_degrees > 0
                        ? static_cast<float>(weight_sum * 2 * std::sin(cap_degrees * M_PI / 720))
                        : 1e30f;
  const auto exclusion = static_cast<int>(std::lround(args.number("exclusion", 0.25) * per_second));
  std::vector<int> clip_of;
  if (args.number("per_clip", 0) != 0) {
    for (int i = 0; i < n; ++i)
      clip_of.push_back(static_cast<int>(features->ClipOf(static_cast<uint64_t>(i) * step)));
  }
  const std::vector<float> thresholds =
      RowThresholds(smooth, args.number("rho", 0.1),
                    static_cast<int>(args.number("neighbours", 0)) / step, exclusion, cap, clip_of);
  std::vector<char> still(n, 0);
  if (args.number("pauses", 1) != 0) {
    auto found = StillFrames(**reader, n, step);
    if (!found.ok()) {
      std::cerr << found.status().ToString() << "\n";
      return 1;
    }
    still = std::move(*found);
  }
  const SquareMatrix sim =
      Similarity(smooth, thresholds, still, static_cast<float>(args.number("penalty", -2)));
  const int min_length =
      std::max(2, static_cast<int>(std::lround(args.number("min_seconds", 0.6) * per_second)));
  const Thumbnail best = FindThumbnail(sim, min_length);
  if (best.fitness < 0) return 0;
  std::printf("%.4f %.4f %.4f %d %d\n", best.fitness, best.score, best.coverage, best.start * step,
              (best.start + best.length) * step);
  for (auto [a, b] : BestFamily(sim, best.start, best.length).segments) {
    std::printf("%d %d\n", a * step, b * step);
  }
  return 0;
}
