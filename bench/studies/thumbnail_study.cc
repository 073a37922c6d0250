// Study: the "thumbnail" of one take (after Müller's audio thumbnailing, Müller, Jiang & Grosche
// 2013): the segment whose best path family in the take's self-similarity matrix explains the
// most of the take, and the segments that family induces, its repetitions. A prototype of
// another way to choose a take's first motif, measured against `motifmine mine` in
// docs/design/motif_quality.md, section 10. Dense: O(n^2) memory and O(n^3) time in the sampled
// frames n, so for single takes and small folders only.
//
//   thumbnail_study ARCHIVE.mfs [step=4] [rho=0.1] [cap_degrees=16] [penalty=-2]
//                   [exclusion=0.25] [min_seconds=0.6] [smooth=1] [pauses=1] [neighbours=0]
//                   [per_clip=0] [candidates=PATHS.mpa] [samples=0] [take_threshold=0]
//                   [trellis_k=0] [held=0] [motifs=1] [min_score=0] [null=0] [null_quantile=0.95]
//                   [from_motifs=MOTIFS.json] [all_motifs=0]
// Prints "fitness score coverage start end" of the thumbnail, then "start end" of every
// segment its family induces (archive frames, end exclusive); with motifs = K, up to K such
// blocks: each next one the best family without the frames of those before, while its score
// (the family's mean similarity) is at least min_score, and (null = C > 0) from the second on
// while its fitness is at least the null_quantile of C random segments' (lengths drawn from the
// candidates, a fixed seed). The archive's clips are taken as one sequence (a path may cross
// from one clip into the next). Measured in docs/design/motif_quality.md, sections 10 and 11.
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
// the segment's own path left out; segments from min_seconds to half the take, or with
// `candidates` only both segments of each path of that paths file (the miner's candidates, as a
// miner at scale would try them) that are at least min_seconds long. samples = M > 0: a row's
// quantile over about M of its columns only (evenly spaced), as a miner would estimate it;
// take_threshold=1: every row gets the median of the rows' thresholds (one per take);
// trellis_k = K > 0: no row's threshold beyond its K-th nearest frame (archive frames), what a
// trellis with k_max = K holds; held=1: candidate segments whose every frame is within the
// middle frame's threshold are not tried; from_motifs=MOTIFS.json: the instances of its top
// motif (all_motifs=1: of every motif) are tried too.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bench/studies/experiment_args.h"
#include "bench/studies/study_archive.h"
#include "engine/cluster/motifs_json.h"
#include "engine/cluster/pauses.h"
#include "formats/paths_file/paths_file_reader.h"

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
                                 int exclusion, float cap, const std::vector<int>& clip_of,
                                 int samples = 0) {
  std::vector<float> thresholds(smooth.n);
  const int stride = samples > 0 ? std::max(1, smooth.n / samples) : 1;
  for (int i = 0; i < smooth.n; ++i) {
    std::vector<float> row;
    for (int j = (i * 7) % stride; j < smooth.n; j += stride) {  // rows see staggered columns
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

// With `segments` (sampled frames), only those are tried; else every segment from min_length
// to half the take.
Thumbnail FindThumbnail(const SquareMatrix& sim, int min_length,
                        const std::vector<std::pair<int, int>>& segments) {
  Thumbnail best;
  const int n = sim.n;
  std::vector<std::pair<int, int>> tried = segments;
  if (tried.empty()) {
    for (int len = min_length; len <= n / 2; len += std::max(1, len / 10)) {
      for (int s = 0; s + len <= n; s += 2) tried.push_back({s, len});
    }
  }
  for (auto [s, len] : tried) {
    if (len < 2 || s + len > n) continue;
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
  return best;
}

// The null model of a family's fitness: the best family of `count` random segments (lengths
// drawn from `segments`, starts uniform, a fixed seed), their `quantile`-quantile fitness.
double NullFitness(const SquareMatrix& sim, const std::vector<std::pair<int, int>>& segments,
                   int count, double quantile) {
  std::mt19937_64 random(7);
  std::vector<double> fitness;
  for (int draw = 0; draw < count && !segments.empty(); ++draw) {
    const int len = segments[random() % segments.size()].second;
    if (len >= sim.n) continue;
    const int start = static_cast<int>(random() % static_cast<uint64_t>(sim.n - len));
    const Thumbnail one = FindThumbnail(sim, len, {{start, len}});
    fitness.push_back(std::max(0.0, one.fitness));
  }
  if (fitness.empty()) return 0;
  const auto rank = static_cast<size_t>(quantile * static_cast<double>(fitness.size() - 1));
  std::nth_element(fitness.begin(), fitness.begin() + static_cast<long>(rank), fitness.end());
  return fitness[rank];
}

// Each sampled row's threshold (the options rho, neighbours, per_clip, samples, trellis_k,
// take_threshold of the header).
std::vector<float> Thresholds(const motif::testing::ExperimentArgs& args,
                              const SquareMatrix& smooth, const motif::PoseFeatures& features,
                              int step, float cap, int exclusion) {
  const int n = smooth.n;
  std::vector<int> clip_of;
  if (args.number("per_clip", 0) != 0) {
    for (int i = 0; i < n; ++i)
      clip_of.push_back(static_cast<int>(features.ClipOf(static_cast<uint64_t>(i) * step)));
  }
  std::vector<float> thresholds = RowThresholds(
      smooth, args.number("rho", 0.1), static_cast<int>(args.number("neighbours", 0)) / step,
      exclusion, cap, clip_of, static_cast<int>(args.number("samples", 0)));
  if (const int k = static_cast<int>(args.number("trellis_k", 0)) / step; k > 0) {
    // Only what a trellis with k_max = K keeps: no threshold beyond the K-th nearest frame.
    const std::vector<float> kept = RowThresholds(smooth, 0, k, exclusion, cap, {});
    for (int i = 0; i < n; ++i) thresholds[i] = std::min(thresholds[i], kept[i]);
  }
  if (args.number("take_threshold", 0) != 0) {  // one threshold for all rows: the rows' median
    std::vector<float> sorted = thresholds;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2),
                     sorted.end());
    std::fill(thresholds.begin(), thresholds.end(), sorted[sorted.size() / 2]);
  }
  return thresholds;
}

// The candidates option: both segments of each path of the paths file, as (start, length) in
// sampled frames, from min_length on; with held=1 not those that barely move (every frame
// within the middle frame's threshold: short pieces of a slow movement tile it otherwise).
motif::Result<std::vector<std::pair<int, int>>> CandidateSegments(
    const std::string& paths_path, int step, int min_length, bool skip_held,
    const SquareMatrix& dist, const std::vector<float>& thresholds) {
  MOTIF_ASSIGN_OR_RETURN(auto paths, motif::PathsFileReader::Open(paths_path));
  std::vector<std::pair<int, int>> segments;
  for (const motif::PathCandidate& path : paths->candidates()) {
    for (auto [a, b] :
         {std::pair{path.top_start, path.top_end}, std::pair{path.match_start, path.match_end}}) {
      const int first = static_cast<int>(a / step);
      const int length = static_cast<int>(b / step) - first;
      if (length < min_length || first + length > dist.n) continue;
      const int middle = first + length / 2;
      bool held = skip_held;
      for (int frame = first; held && frame < first + length; ++frame) {
        held = dist.at(middle, frame) <= thresholds[middle];
      }
      if (!held) segments.push_back({first, length});
    }
  }
  return segments;
}

// The from_motifs option: the instances of a motifs.json's top motif (with all, of every motif),
// as (start, length) in sampled frames.
motif::Result<std::vector<std::pair<int, int>>> MotifSegments(const std::string& motifs_path,
                                                              bool all, int step, int n) {
  MOTIF_ASSIGN_OR_RETURN(const motif::MotifsDocument document, motif::ReadMotifsJson(motifs_path));
  const size_t used = all ? document.motifs.size() : std::min<size_t>(1, document.motifs.size());
  std::vector<std::pair<int, int>> segments;
  for (size_t motif = 0; motif < used; ++motif) {
    for (const motif::MotifsJsonInstance& instance : document.motifs[motif].instances) {
      const int first = static_cast<int>(instance.frame / step);
      const int length =
          static_cast<int>((instance.frame + instance.end - instance.start) / step) - first;
      if (length >= 2 && first + length <= n) segments.push_back({first, length});
    }
  }
  return segments;
}

// Prints up to `motifs` families (the header's output), each next one without the frames of
// those before (their rows and columns score `penalty`) and without the candidates they overlap.
void PrintFamilies(const motif::testing::ExperimentArgs& args, SquareMatrix open, int min_length,
                   std::vector<std::pair<int, int>> segments, int step) {
  const auto penalty = static_cast<float>(args.number("penalty", -2));
  const int motifs = std::max(1, static_cast<int>(args.number("motifs", 1)));
  const bool from_candidates = !segments.empty();
  for (int motif = 0; motif < motifs; ++motif) {
    const Thumbnail best = FindThumbnail(open, min_length, segments);
    if (best.fitness < 0 || best.score < args.number("min_score", 0)) break;
    if (motif > 0 && args.number("null", 0) > 0 &&
        best.fitness < NullFitness(open, segments, static_cast<int>(args.number("null", 0)),
                                   args.number("null_quantile", 0.95))) {
      break;
    }
    std::printf("%.4f %.4f %.4f %d %d\n", best.fitness, best.score, best.coverage,
                best.start * step, (best.start + best.length) * step);
    const Family family = BestFamily(open, best.start, best.length);
    for (auto [a, b] : family.segments) std::printf("%d %d\n", a * step, b * step);
    for (auto [a, b] : family.segments) {
      for (int frame = a; frame < b; ++frame) {
        for (int other = 0; other < open.n; ++other) {
          open.at(frame, other) = open.at(other, frame) = penalty;
        }
      }
    }
    if (!from_candidates) continue;
    std::erase_if(segments, [&](std::pair<int, int> segment) {
      for (auto [a, b] : family.segments) {
        if (segment.first < b && a < segment.first + segment.second) return true;
      }
      return false;
    });
    if (segments.empty()) break;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: thumbnail_study ARCHIVE.mfs [step=4] [rho=0.1] [cap_degrees=16] "
                 "[penalty=-2] [exclusion=0.25] [min_seconds=0.6] [smooth=1] [pauses=1] "
                 "[neighbours=0] [per_clip=0] [candidates=PATHS.mpa] [samples=0] "
                 "[take_threshold=0] [trellis_k=0] [held=0] [motifs=1] [min_score=0] [null=0] "
                 "[null_quantile=0.95] [from_motifs=MOTIFS.json] [all_motifs=0]\n";
    return 2;
  }
  const motif::testing::ExperimentArgs args(argc - 1, argv + 1);
  const int step = std::max(1, static_cast<int>(args.number("step", 4)));
  auto archive = motif::testing::OpenStudyArchive(argv[1]);
  if (!archive.ok()) {
    std::cerr << archive.status().ToString() << "\n";
    return 1;
  }
  const motif::FrameFileReader& reader = *archive->reader;
  const motif::PoseFeatures& features = archive->features;
  const double per_second = reader.fps() / step;
  const int n = static_cast<int>(features.frame_count() / step);
  const SquareMatrix dist = Distances(features, n, step);
  const SquareMatrix smooth =
      args.number("smooth", 1) != 0
          ? EnhancePaths(dist, std::max(1, static_cast<int>(std::lround(0.25 * per_second))))
          : dist;
  double weight_sum = 0;
  for (float weight : features.weights()) weight_sum += weight;
  const double cap_degrees = args.number("cap_degrees", 16);
  const float cap = cap_degrees > 0
                        ? static_cast<float>(weight_sum * 2 * std::sin(cap_degrees * M_PI / 720))
                        : 1e30f;
  const auto exclusion = static_cast<int>(std::lround(args.number("exclusion", 0.25) * per_second));
  const std::vector<float> thresholds = Thresholds(args, smooth, features, step, cap, exclusion);
  std::vector<char> still(n, 0);
  if (args.number("pauses", 1) != 0) {
    auto found = StillFrames(reader, n, step);
    if (!found.ok()) {
      std::cerr << found.status().ToString() << "\n";
      return 1;
    }
    still = std::move(*found);
  }
  const int min_length =
      std::max(2, static_cast<int>(std::lround(args.number("min_seconds", 0.6) * per_second)));
  std::vector<std::pair<int, int>> segments;
  if (args.has("candidates")) {
    auto found = CandidateSegments(args.text("candidates"), step, min_length,
                                   args.number("held", 0) != 0, dist, thresholds);
    if (!found.ok()) {
      std::cerr << found.status().ToString() << "\n";
      return 1;
    }
    segments = std::move(*found);
  }
  if (args.has("from_motifs")) {
    auto found =
        MotifSegments(args.text("from_motifs"), args.number("all_motifs", 0) != 0, step, n);
    if (!found.ok()) {
      std::cerr << found.status().ToString() << "\n";
      return 1;
    }
    segments.insert(segments.end(), found->begin(), found->end());
  }
  if ((args.has("candidates") || args.has("from_motifs")) && segments.empty()) return 0;
  PrintFamilies(
      args, Similarity(smooth, thresholds, still, static_cast<float>(args.number("penalty", -2))),
      min_length, std::move(segments), step);
  return 0;
}
