// Study: which distance between short stretches of motion tells two performances of one
// movement from two different movements, measured before mining with it
// (docs/design/motion_distance.md has the definitions, the results and the commands).
//
// For each annotated occurrence of one labelled take (the query), every other stretch of the
// same take is ranked by each candidate distance, trivial overlaps excluded (stretch_ranking.h
// defines the stretches, the positives and the scores). Measures, per candidate: the fraction of
// queries whose nearest stretch is another occurrence of the same movement (1-NN), the ROC AUC
// of same-movement stretches against the others (pooled over the take's queries, and per query),
// the cost of one evaluation between two 1 s stretches and of one column pair (single thread,
// median of `repeats` runs), and how the column distances are distributed: quantiles over random
// column pairs at least 0.25 s apart, and where the columns of two occurrences of one movement,
// aligned by the candidate's own cheapest warp, fall among them (a percentile of the take).
//
//   distance_study ARCHIVE.mfs TRUTH.tsv [clip=NAME] [candidates=a,b,...] [embedding=FILE.mwe]
//                  [frame_grid=2] [samples=32] [word_frames=16] [word_stride=4]
//                  [start_stride=4] [min_scale=0.5] [max_scale=2] [scale_steps=9]
//                  [mp_window=0.33] [mp_floor=0.01] [warp_band=0] [exclusion=0.25]
//                  [random_pairs=20000] [timing_pairs=200] [repeats=5] [seed=1]
//                  [out=ROWS.tsv] [movements_out=MOVEMENTS.tsv]
// ARCHIVE: `motifmine import` of the take; TRUTH: its repetitions tsv (clip frames). clip: the
// clip to study (default: the first clip of TRUTH that the archive has). Prints a table; `out`
// appends one TSV row per candidate, `movements_out` one per candidate and movement.
// Candidates (column_distances.h for the parts): quat_dtw quat_lock pos_dtw pos_lock posvel_dtw
// posvel_lock mp_stretch mp_win_dtw arms_dtw legs_dtw word_dtw word_lock embed_dtw embed_lock
// (with embedding=) parts_min parts_active. warp_band > 0 limits every warp to a Sakoe-Chiba band
// of that fraction of the longer side (0: unconstrained, as the clustering warps).
// Every random choice (timing pairs, random column pairs) comes from SplitMix64(seed).
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bench/studies/body_frame_features.h"
#include "bench/studies/column_distances.h"
#include "bench/studies/experiment_args.h"
#include "bench/studies/stretch_ranking.h"
#include "bench/studies/study_archive.h"
#include "common/split_mix64.h"
#include "engine/cluster/warped_similarity.h"
#include "engine/embedding/embedding_file.h"
#include "engine/evaluation/motif_truth.h"
#include "engine/signature/clip_words.h"
#include "engine/words/word_embedder.h"
#include "formats/tensor_file/tensor_file.h"

namespace {

using motif::testing::ColumnDistance;
using motif::testing::ColumnGrid;
using motif::testing::ColumnMatrix;
using motif::testing::Span;
using motif::testing::Stretch;

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// The CPU time of this thread, in seconds: the machine is shared, and time spent descheduled is
// not the distance's cost.
double ThreadSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Nanoseconds per call of `batch` (which makes `calls` calls), the median of `repeats` runs.
double NanosPerCall(const std::function<double()>& batch, size_t calls, int repeats) {
  std::vector<double> runs;
  volatile double sink = 0;
  for (int run = 0; run < repeats; ++run) {
    const double started = ThreadSeconds();
    sink = sink + batch();
    runs.push_back((ThreadSeconds() - started) * 1e9 /
                   static_cast<double>(std::max<size_t>(1, calls)));
  }
  return Median(runs);
}

struct Timing {
  double pair_ns = 0;         // one evaluation between two 1 s stretches
  double column_pair_ns = 0;  // one column distance (0: no columns)
  double column_ns = 0;       // one column's features from the frames' (mp_stretch: a stretch's)
  double frame_ns = 0;        // one frame's features from the archive row
};

// One candidate distance between stretches.
class Candidate {
 public:
  Candidate(std::string name, std::string column, std::string properties)
      : name_(std::move(name)), column_(std::move(column)), properties_(std::move(properties)) {}
  virtual ~Candidate() = default;
  const std::string& name() const { return name_; }
  const std::string& column() const { return column_; }
  const std::string& properties() const { return properties_; }

  // Query's distance to each stretch.
  virtual std::vector<float> Rank(const Span& query, const std::vector<Stretch>& stretches) = 0;
  // The cost of one evaluation and of the columns, on `pairs` of stretches.
  virtual Timing Time(const std::vector<std::pair<Span, Span>>& pairs, int repeats,
                      motif::SplitMix64* random) const = 0;
  // One evaluation without precomputed cells (what Time measures).
  virtual double Evaluate(const Span& a, const Span& b) const = 0;
  // Frees what ranking needed.
  virtual void Release() {}
  // What the table should say besides the scores (empty: nothing).
  virtual std::string Note() const { return ""; }

 private:
  std::string name_;
  std::string column_;
  std::string properties_;
};

// A column distance along the cheapest warp or in lock step (column_distances.h).
class ColumnCandidate : public Candidate {
 public:
  ColumnCandidate(std::string name, std::string column, std::string properties, ColumnGrid grid,
                  std::shared_ptr<const ColumnDistance> distance, bool warp, double column_ns,
                  double frame_ns, double band = 0)
      : Candidate(std::move(name), std::move(column), std::move(properties)),
        grid_(grid),
        distance_(std::move(distance)),
        warp_(warp),
        band_(band),
        column_ns_(column_ns),
        frame_ns_(frame_ns) {}

  const ColumnGrid& grid() const { return grid_; }
  const ColumnDistance& distance() const { return *distance_; }
  // The Sakoe-Chiba band in columns for an m x n warp (0: none).
  int BandCells(size_t m, size_t n) const {
    if (band_ <= 0) return 0;
    return std::max(1, static_cast<int>(std::ceil(band_ * static_cast<double>(std::max(m, n)))));
  }
  const ColumnMatrix& matrix() {
    if (!matrix_) matrix_.emplace(*distance_);
    return *matrix_;
  }
  void Release() override { matrix_.reset(); }

  std::vector<float> Rank(const Span& query, const std::vector<Stretch>& stretches) override {
    const ColumnMatrix& cells = matrix();
    const std::vector<uint32_t> a = grid_.Columns(query);
    std::vector<float> out;
    out.reserve(stretches.size());
    for (const Stretch& stretch : stretches) {
      const std::vector<uint32_t> b = grid_.Columns(stretch.span, warp_ ? 0 : a.size());
      out.push_back(static_cast<float>(Aggregate(a, b, [&](uint32_t i, uint32_t j) {
        return static_cast<double>(cells.at(a[i], b[j]));
      })));
    }
    return out;
  }

  double Evaluate(const Span& x, const Span& y) const override {
    const std::vector<uint32_t> a = grid_.Columns(x);
    const std::vector<uint32_t> b = grid_.Columns(y, warp_ ? 0 : a.size());
    return Aggregate(a, b, [&](uint32_t i, uint32_t j) {
      return static_cast<double>(distance_->Distance(a[i], b[j]));
    });
  }

  Timing Time(const std::vector<std::pair<Span, Span>>& pairs, int repeats,
              motif::SplitMix64* random) const override {
    Timing timing;
    timing.column_ns = column_ns_;
    timing.frame_ns = frame_ns_;
    timing.pair_ns = NanosPerCall(
        [&] {
          double total = 0;
          for (const auto& [a, b] : pairs) total += Evaluate(a, b);
          return total;
        },
        pairs.size(), repeats);
    std::vector<std::pair<uint32_t, uint32_t>> columns;
    for (int idx = 0; idx < 20000; ++idx) {
      columns.push_back({static_cast<uint32_t>(random->Below(distance_->count())),
                         static_cast<uint32_t>(random->Below(distance_->count()))});
    }
    timing.column_pair_ns = NanosPerCall(
        [&] {
          double total = 0;
          for (const auto& [a, b] : columns) total += distance_->Distance(a, b);
          return total;
        },
        columns.size(), repeats);
    return timing;
  }

 private:
  template <class Cost>
  double Aggregate(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b,
                   const Cost& cost) const {
    if (warp_) {
      return motif::testing::MeanWarp(static_cast<uint32_t>(a.size()),
                                      static_cast<uint32_t>(b.size()), cost,
                                      BandCells(a.size(), b.size()));
    }
    return motif::testing::LockStep(static_cast<uint32_t>(a.size()), cost);
  }

  ColumnGrid grid_;
  std::shared_ptr<const ColumnDistance> distance_;
  bool warp_;
  double band_;
  double column_ns_;
  double frame_ns_;
  std::optional<ColumnMatrix> matrix_;
};

// The matrix-profile distance between whole stretches (ZNormalisedStretch).
class ZNormalisedStretchCandidate : public Candidate {
 public:
  ZNormalisedStretchCandidate(const motif::testing::BodyFrameFeatures& body,
                              motif::testing::ChannelSet channels, uint32_t samples, double floor,
                              double body_ns)
      : Candidate("mp_stretch", "the whole stretch",
                  "metric on the z-normalised vector; embeddable (L2)"),
        body_(&body),
        channels_(std::move(channels)),
        samples_(samples),
        floor_(floor),
        body_ns_(body_ns) {}

  std::vector<float> Rank(const Span& query, const std::vector<Stretch>& stretches) override {
    const std::vector<float> a = Vector(query);
    std::vector<float> out;
    out.reserve(stretches.size());
    for (const Stretch& stretch : stretches) {
      out.push_back(motif::testing::RootMeanSquareDifference(a, Vector(stretch.span)));
    }
    return out;
  }

  double Evaluate(const Span& a, const Span& b) const override {
    return motif::testing::RootMeanSquareDifference(Vector(a), Vector(b));
  }

  // The pair: two vectors made beforehand (as an index would hold them); the column: making one
  // vector from the frames' body-frame features.
  Timing Time(const std::vector<std::pair<Span, Span>>& pairs, int repeats,
              motif::SplitMix64*) const override {
    std::vector<std::pair<std::vector<float>, std::vector<float>>> vectors;
    for (const auto& [a, b] : pairs) vectors.push_back({Vector(a), Vector(b)});
    Timing timing;
    timing.pair_ns = NanosPerCall(
        [&] {
          double total = 0;
          for (const auto& [a, b] : vectors)
            total += motif::testing::RootMeanSquareDifference(a, b);
          return total;
        },
        vectors.size(), repeats);
    timing.column_ns = NanosPerCall(
        [&] {
          double total = 0;
          for (const auto& pair : pairs) total += Vector(pair.first)[0];
          return total;
        },
        pairs.size(), repeats);
    timing.frame_ns = body_ns_;
    return timing;
  }

 private:
  std::vector<float> Vector(const Span& span) const {
    return motif::testing::ZNormalisedStretch(*body_, channels_, span, samples_, floor_);
  }

  const motif::testing::BodyFrameFeatures* body_;
  motif::testing::ChannelSet channels_;
  uint32_t samples_;
  double floor_;
  double body_ns_;
};

// The least of several distances, each divided by its median over the query's stretches (so a
// body part that repeats while the others do not still finds the repetition).
class LeastPartCandidate : public Candidate {
 public:
  explicit LeastPartCandidate(std::vector<Candidate*> parts)
      : Candidate("parts_min", "the parts' columns",
                  "not a metric (a minimum of metrics); one LSH table per part, candidates united"),
        parts_(std::move(parts)) {}

  std::vector<float> Rank(const Span& query, const std::vector<Stretch>& stretches) override {
    std::vector<float> out(stretches.size(), std::numeric_limits<float>::infinity());
    for (Candidate* part : parts_) {
      const std::vector<float> distances = part->Rank(query, stretches);
      std::vector<double> sorted(distances.begin(), distances.end());
      const double median = std::max(Median(sorted), 1e-12);
      for (size_t idx = 0; idx < out.size(); ++idx) {
        out[idx] = std::min(out[idx], static_cast<float>(distances[idx] / median));
      }
    }
    return out;
  }

  // The parts' evaluations and their least, unnormalised: the medians belong to a query's whole
  // ranking, and the cost is the same.
  double Evaluate(const Span& a, const Span& b) const override {
    double least = std::numeric_limits<double>::infinity();
    for (const Candidate* part : parts_) least = std::min(least, part->Evaluate(a, b));
    return least;
  }

  Timing Time(const std::vector<std::pair<Span, Span>>& pairs, int repeats,
              motif::SplitMix64* random) const override {
    Timing timing;
    for (const Candidate* part : parts_) {
      const Timing one = part->Time(pairs, repeats, random);
      timing.pair_ns += one.pair_ns;
      timing.column_pair_ns += one.column_pair_ns;
      timing.column_ns += one.column_ns;
      timing.frame_ns = std::max(timing.frame_ns, one.frame_ns);  // the same frames' features
    }
    return timing;
  }

  void Release() override {
    for (Candidate* part : parts_) part->Release();
  }

 private:
  std::vector<Candidate*> parts_;
};

// The body parts that carry the query's movement, compared alone: a part is active when it moves
// (the mean square of its velocity channels over the query) at least half as much, relative to
// how much it moves over the whole take, as the part that moves most so; the cell cost is the
// root mean square difference over the active parts' channels together (the arms in the chest
// frame; the legs with the root motion), along the cheapest warp. A punch thrown while the
// feet keep bouncing is then compared by the arms, a step while the arms lead a partner by the
// legs, and a movement of the whole body by both.
class ActivePartsCandidate : public Candidate {
 public:
  ActivePartsCandidate(ColumnCandidate* arms, ColumnCandidate* legs,
                       const motif::testing::BodyFrameFeatures& body)
      : Candidate("parts_active", "frame",
                  "column: L2 on the active parts' vector (metric for a fixed choice; one LSH "
                  "table per choice); stretch: warp, not a metric"),
        parts_{arms, legs},
        channels_{static_cast<double>(body.Arms().size()), static_cast<double>(body.Legs().size())},
        motion_{SquaredSpeeds(body, body.ArmVelocities()),
                SquaredSpeeds(body, body.LegVelocities())} {
    for (int part = 0; part < 2; ++part) {
      take_motion_[part] = MeanOver(motion_[part], Span{0, motion_[part].size()});
    }
  }

  std::vector<float> Rank(const Span& query, const std::vector<Stretch>& stretches) override {
    const std::array<bool, 2> active = Active(query);
    ++choices_[active[0] && active[1] ? 2 : (active[0] ? 0 : 1)];
    const ColumnMatrix& arms = parts_[0]->matrix();
    const ColumnMatrix& legs = parts_[1]->matrix();
    const ColumnGrid& grid = parts_[0]->grid();
    const std::vector<uint32_t> a = grid.Columns(query);
    std::vector<float> out;
    out.reserve(stretches.size());
    for (const Stretch& stretch : stretches) {
      const std::vector<uint32_t> b = grid.Columns(stretch.span);
      out.push_back(static_cast<float>(motif::testing::MeanWarp(
          static_cast<uint32_t>(a.size()), static_cast<uint32_t>(b.size()),
          [&](uint32_t i, uint32_t j) {
            return Combine(active, arms.at(a[i], b[j]), legs.at(a[i], b[j]));
          },
          parts_[0]->BandCells(a.size(), b.size()))));
    }
    return out;
  }

  double Evaluate(const Span& x, const Span& y) const override {
    const std::array<bool, 2> active = Active(x);
    const ColumnGrid& grid = parts_[0]->grid();
    const std::vector<uint32_t> a = grid.Columns(x);
    const std::vector<uint32_t> b = grid.Columns(y);
    return motif::testing::MeanWarp(
        static_cast<uint32_t>(a.size()), static_cast<uint32_t>(b.size()),
        [&](uint32_t i, uint32_t j) {
          return Combine(active, active[0] ? parts_[0]->distance().Distance(a[i], b[j]) : 0.0f,
                         active[1] ? parts_[1]->distance().Distance(a[i], b[j]) : 0.0f);
        },
        parts_[0]->BandCells(a.size(), b.size()));
  }

  Timing Time(const std::vector<std::pair<Span, Span>>& pairs, int repeats,
              motif::SplitMix64* random) const override {
    Timing timing = parts_[0]->Time(pairs, repeats, random);
    const Timing legs = parts_[1]->Time(pairs, repeats, random);
    timing.column_pair_ns += legs.column_pair_ns;
    timing.pair_ns = NanosPerCall(
        [&] {
          double total = 0;
          for (const auto& [a, b] : pairs) total += Evaluate(a, b);
          return total;
        },
        pairs.size(), repeats);
    return timing;
  }

  void Release() override {
    for (ColumnCandidate* part : parts_) part->Release();
  }

  std::string Note() const override {
    return "queries by arms " + std::to_string(choices_[0]) + ", legs " +
           std::to_string(choices_[1]) + ", both " + std::to_string(choices_[2]);
  }

 private:
  static std::vector<double> SquaredSpeeds(const motif::testing::BodyFrameFeatures& body,
                                           const motif::testing::ChannelSet& channels) {
    std::vector<double> out(body.frame_count(), 0.0);
    for (uint64_t frame = 0; frame < body.frame_count(); ++frame) {
      for (uint32_t channel : channels)
        out[frame] += body.frame(frame)[channel] * body.frame(frame)[channel];
    }
    return out;
  }

  static double MeanOver(const std::vector<double>& values, const Span& span) {
    double total = 0;
    for (uint64_t frame = span.start; frame < span.end && frame < values.size(); ++frame) {
      total += values[frame];
    }
    return total / static_cast<double>(std::max<uint64_t>(1, span.length()));
  }

  std::array<bool, 2> Active(const Span& query) const {
    std::array<double, 2> relative{};
    for (int part = 0; part < 2; ++part) {
      relative[part] = MeanOver(motion_[part], query) / std::max(take_motion_[part], 1e-12);
    }
    const double most = std::max(relative[0], relative[1]);
    return {relative[0] >= 0.5 * most, relative[1] >= 0.5 * most};
  }

  double Combine(const std::array<bool, 2>& active, float arms, float legs) const {
    double sum = 0;
    double weight = 0;
    if (active[0]) sum += channels_[0] * arms * arms, weight += channels_[0];
    if (active[1]) sum += channels_[1] * legs * legs, weight += channels_[1];
    return std::sqrt(sum / weight);
  }

  std::array<ColumnCandidate*, 2> parts_;
  std::array<double, 2> channels_;
  std::array<std::vector<double>, 2> motion_;
  std::array<double, 2> take_motion_{};
  std::array<int, 3> choices_{};
};

}  // namespace

namespace {

// What the candidates are built from: one clip of the archive.
struct ClipData {
  const motif::FrameFileReader* reader = nullptr;
  const motif::PoseFeatures* features = nullptr;
  size_t clip_idx = 0;
  motif::ClipInfo info;
  std::vector<float> rows;
  std::vector<float> joint_weights;
  std::optional<motif::testing::BodyFrameFeatures> body;
  double body_ns = 0;  // body-frame features per frame
  double quat_ns = 0;  // pose features (quantised quaternions) per frame
};

struct StudyOptions {
  uint32_t frame_grid = 2;
  uint32_t samples = 32;
  uint32_t word_stride = 4;
  uint32_t word_frames = 16;
  double mp_window = 0.33;
  double mp_floor = 0.01;
  double warp_band = 0;
  int repeats = 5;
};

motif::Result<ClipData> LoadClip(const motif::testing::StudyArchive& archive, size_t clip_idx,
                                 int repeats) {
  ClipData data;
  data.reader = archive.reader.get();
  data.features = &archive.features;
  data.clip_idx = clip_idx;
  data.info = data.reader->clips()[clip_idx];
  MOTIF_RETURN_IF_ERROR(
      data.reader->ReadFrames(data.info.first_frame, data.info.frame_count, &data.rows));
  MOTIF_ASSIGN_OR_RETURN(data.joint_weights,
                         motif::LoadDistanceWeights(data.reader->skeleton(), ""));
  std::vector<double> body_runs;
  std::vector<double> quat_runs;
  for (int run = 0; run < repeats; ++run) {
    double started = ThreadSeconds();
    MOTIF_ASSIGN_OR_RETURN(
        auto body, motif::testing::BodyFrameFeatures::Compute(data.reader->skeleton(), data.info,
                                                              data.rows, data.reader->fps()));
    body_runs.push_back((ThreadSeconds() - started) * 1e9 /
                        static_cast<double>(data.info.frame_count));
    data.body.emplace(std::move(body));
    started = ThreadSeconds();
    const motif::PoseFeatures quantised =
        motif::PoseFeatures::FromRows(data.rows.data(), data.info.frame_count,
                                      data.reader->layout().joint_count, data.joint_weights, {0});
    quat_runs.push_back((ThreadSeconds() - started) * 1e9 /
                        static_cast<double>(quantised.frame_count()));
  }
  data.body_ns = Median(body_runs);
  data.quat_ns = Median(quat_runs);
  return data;
}

ColumnGrid FrameGrid(const ClipData& data, const StudyOptions& options) {
  ColumnGrid grid;
  grid.kind = ColumnGrid::Kind::kFrames;
  grid.spacing = options.frame_grid;
  grid.count =
      static_cast<uint32_t>((data.info.frame_count + options.frame_grid - 1) / options.frame_grid);
  grid.samples = options.samples;
  return grid;
}

// The words of the clip, one every word sample (the `segment` words are every word_stride-th).
struct ClipWordColumns {
  ColumnGrid grid;
  motif::WordBatch batch;
  std::optional<motif::WordDistance> distance;
};

motif::Result<ClipWordColumns> LoadWords(const ClipData& data, const StudyOptions& options) {
  motif::WordOptions word_options;
  word_options.stride_frames = 1;
  word_options.word_frames = options.word_frames;
  MOTIF_ASSIGN_OR_RETURN(
      const motif::ClipWords words,
      motif::ClipWords::Read(*data.reader, data.clip_idx, data.joint_weights, word_options));
  ClipWordColumns out;
  words.AllWords(&out.batch, /*keep_rows=*/true);
  if (out.batch.empty()) return motif::Status::InvalidArgument("the clip is shorter than a word");
  const motif::WordGrid& grid = words.grid();
  out.grid.kind = ColumnGrid::Kind::kWords;
  out.grid.count = static_cast<uint32_t>(out.batch.size());
  out.grid.first_centre = grid.SourceTime(0.5 * (word_options.word_frames - 1));
  out.grid.spacing = grid.SourceTime(1.0) - grid.SourceTime(0.0);
  out.grid.samples = options.samples;
  out.grid.word_spacing = options.word_stride * out.grid.spacing;
  out.distance.emplace(words.resampler().weights(), word_options.word_frames);
  return out;
}

std::shared_ptr<const ColumnDistance> WordDtw(const ClipWordColumns& words, int repeats,
                                              double* column_ns) {
  std::vector<motif::PreparedWord> prepared(words.batch.size());
  std::vector<double> runs;
  for (int run = 0; run < repeats; ++run) {
    const double started = ThreadSeconds();
    for (size_t word = 0; word < words.batch.size(); ++word) {
      words.distance->Prepare(words.batch.word(word), &prepared[word]);
    }
    runs.push_back((ThreadSeconds() - started) * 1e9 / static_cast<double>(words.batch.size()));
  }
  *column_ns = Median(runs);
  return std::make_shared<motif::testing::WordDtwColumns>(*words.distance, std::move(prepared));
}

motif::Result<std::shared_ptr<const ColumnDistance>> Embeddings(const ClipData& data,
                                                                const ClipWordColumns& words,
                                                                const std::string& path,
                                                                int repeats, double* column_ns) {
  MOTIF_ASSIGN_OR_RETURN(const motif::TensorFile file,
                         motif::ReadTensorFile(path, motif::kEmbeddingKind));
  MOTIF_ASSIGN_OR_RETURN(const motif::EmbeddingModel model, motif::EmbeddingFromTensorFile(file));
  if (model.net.shape().frames != words.batch.word_frames()) {
    return motif::Status::InvalidArgument("the embedding's words have " +
                                          std::to_string(model.net.shape().frames) + " frames");
  }
  MOTIF_ASSIGN_OR_RETURN(
      const motif::WordEmbedder embedder,
      motif::WordEmbedder::Create(model, data.reader->layout(), data.joint_weights, /*threads=*/1));
  motif::RowMatrixXf embedded(static_cast<Eigen::Index>(words.batch.size()), embedder.dims());
  std::vector<double> runs;
  for (int run = 0; run < repeats; ++run) {
    const double started = ThreadSeconds();
    embedder.Embed(words.batch, &embedded);
    runs.push_back((ThreadSeconds() - started) * 1e9 / static_cast<double>(words.batch.size()));
  }
  *column_ns = Median(runs);
  std::vector<float> values(embedded.data(), embedded.data() + embedded.size());
  return std::shared_ptr<const ColumnDistance>(
      std::make_shared<motif::testing::VectorColumns>(std::move(values), embedder.dims(), 1.0));
}

// Properties of each kind of column distance, for the table.
const char* kQuatProperties =
    "column: metric (a sum of sign-free chordal distances), hashed via the q q^T embedding";
const char* kVectorProperties = "column: L2 on a vector (metric, LSH-ready)";
const char* kWordProperties = "column: DTW (not a metric, no fixed-length vector)";
const char* kWarpNote = "; stretch: warp, not a metric";
const char* kLockNote = "; stretch: lock step = L2 of the concatenated columns";

std::string Properties(const char* column, bool warp) {
  return std::string(column) + (warp ? kWarpNote : kLockNote);
}

struct CandidateSet {
  double band = 0;  // the warps' Sakoe-Chiba band, a fraction of the longer side (0: none)
  std::vector<std::unique_ptr<Candidate>> owned;
  std::vector<Candidate*> order;  // as run
};

void AddColumn(CandidateSet* set, const std::string& name, const std::string& column,
               const char* properties, const ColumnGrid& grid,
               std::shared_ptr<const ColumnDistance> distance, bool warp, double column_ns,
               double frame_ns) {
  set->owned.push_back(std::make_unique<ColumnCandidate>(name, column, Properties(properties, warp),
                                                         grid, std::move(distance), warp, column_ns,
                                                         frame_ns, set->band));
  set->order.push_back(set->owned.back().get());
}

void AddBodyCandidates(const ClipData& data, const StudyOptions& options, CandidateSet* set) {
  const motif::testing::BodyFrameFeatures& body = *data.body;
  const ColumnGrid grid = FrameGrid(data, options);
  auto quat = std::make_shared<motif::testing::QuatColumns>(*data.features, data.info.first_frame,
                                                            grid, data.info.frame_count);
  AddColumn(set, "quat_dtw", "frame", kQuatProperties, grid, quat, true, 0, data.quat_ns);
  AddColumn(set, "quat_lock", "frame", kQuatProperties, grid, quat, false, 0, data.quat_ns);
  auto pos = std::make_shared<motif::testing::VectorColumns>(
      motif::testing::BodyColumns(body, body.Positions(), grid));
  AddColumn(set, "pos_dtw", "frame", kVectorProperties, grid, pos, true, 0, data.body_ns);
  AddColumn(set, "pos_lock", "frame", kVectorProperties, grid, pos, false, 0, data.body_ns);
  auto posvel = std::make_shared<motif::testing::VectorColumns>(
      motif::testing::BodyColumns(body, body.PositionsAndVelocities(), grid));
  AddColumn(set, "posvel_dtw", "frame", kVectorProperties, grid, posvel, true, 0, data.body_ns);
  AddColumn(set, "posvel_lock", "frame", kVectorProperties, grid, posvel, false, 0, data.body_ns);
  set->owned.push_back(std::make_unique<ZNormalisedStretchCandidate>(
      body, body.PositionsAndVelocities(), options.samples, options.mp_floor, data.body_ns));
  set->order.push_back(set->owned.back().get());
  const double sample_frames = data.reader->fps() / 24.0;
  const auto window_samples =
      std::max<uint32_t>(2, static_cast<uint32_t>(std::lround(options.mp_window * 24.0)));
  std::vector<double> runs;
  std::shared_ptr<const ColumnDistance> windows;
  for (int run = 0; run < options.repeats; ++run) {
    const double started = ThreadSeconds();
    windows = std::make_shared<motif::testing::VectorColumns>(
        motif::testing::ZNormalisedWindowColumns(body, body.PositionsAndVelocities(), grid,
                                                 window_samples, sample_frames, options.mp_floor));
    runs.push_back((ThreadSeconds() - started) * 1e9 / grid.count);
  }
  AddColumn(set, "mp_win_dtw", "window of " + std::to_string(window_samples) + " frames at 24 Hz",
            kVectorProperties, grid, windows, true, Median(runs), data.body_ns);
  auto arms = std::make_shared<motif::testing::VectorColumns>(
      motif::testing::BodyColumns(body, body.Arms(), grid));
  AddColumn(set, "arms_dtw", "frame", kVectorProperties, grid, arms, true, 0, data.body_ns);
  auto legs = std::make_shared<motif::testing::VectorColumns>(
      motif::testing::BodyColumns(body, body.Legs(), grid));
  AddColumn(set, "legs_dtw", "frame", kVectorProperties, grid, legs, true, 0, data.body_ns);
}

motif::Status AddWordCandidates(const ClipData& data, const StudyOptions& options,
                                const std::string& embedding, ClipWordColumns* words,
                                CandidateSet* set) {
  double column_ns = 0;
  auto word_dtw = WordDtw(*words, options.repeats, &column_ns);
  const std::string word =
      "motion word (" + std::to_string(words->batch.word_frames()) + " frames at 24 Hz)";
  AddColumn(set, "word_dtw", word, kWordProperties, words->grid, word_dtw, true, column_ns,
            data.quat_ns);
  AddColumn(set, "word_lock", word, kWordProperties, words->grid, word_dtw, false, column_ns,
            data.quat_ns);
  if (embedding.empty()) return motif::Status::Ok();
  MOTIF_ASSIGN_OR_RETURN(auto embedded,
                         Embeddings(data, *words, embedding, options.repeats, &column_ns));
  AddColumn(set, "embed_dtw", word, kVectorProperties, words->grid, embedded, true, column_ns,
            data.quat_ns);
  AddColumn(set, "embed_lock", word, kVectorProperties, words->grid, embedded, false, column_ns,
            data.quat_ns);
  return motif::Status::Ok();
}

// parts_min over posvel_dtw, arms_dtw and legs_dtw, and parts_active over arms_dtw and
// legs_dtw (added after them).
void AddPartCandidates(const motif::testing::BodyFrameFeatures& body, CandidateSet* set) {
  std::map<std::string, Candidate*> by_name;
  for (Candidate* candidate : set->order) by_name[candidate->name()] = candidate;
  set->owned.push_back(std::make_unique<LeastPartCandidate>(std::vector<Candidate*>{
      by_name.at("posvel_dtw"), by_name.at("arms_dtw"), by_name.at("legs_dtw")}));
  set->order.push_back(set->owned.back().get());
  set->owned.push_back(std::make_unique<ActivePartsCandidate>(
      static_cast<ColumnCandidate*>(by_name.at("arms_dtw")),
      static_cast<ColumnCandidate*>(by_name.at("legs_dtw")), body));
  set->order.push_back(set->owned.back().get());
}

}  // namespace

namespace {

// How a candidate's column distances are distributed in the take (header).
struct ColumnStats {
  bool present = false;
  double random_q05 = 0, random_q10 = 0, random_q50 = 0;
  double aligned_median = 0;      // absolute
  double aligned_pct_median = 0;  // percentile among the random pairs
  double aligned_pct_p90 = 0;
  double aligned_within_q10 = 0;  // fraction of aligned cells at or below random_q10
  uint64_t aligned_cells = 0;
};

double Quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0;
  return sorted[std::min(sorted.size() - 1, static_cast<size_t>(q * sorted.size()))];
}

std::vector<double> RandomColumnPairs(ColumnCandidate& candidate, double exclusion_frames,
                                      int pairs, motif::SplitMix64* random) {
  const ColumnMatrix& cells = candidate.matrix();
  const ColumnGrid& grid = candidate.grid();
  std::vector<double> values;
  for (int attempt = 0; attempt < 50 * pairs && static_cast<int>(values.size()) < pairs;
       ++attempt) {
    const auto a = static_cast<uint32_t>(random->Below(grid.count));
    const auto b = static_cast<uint32_t>(random->Below(grid.count));
    if (std::abs(grid.Centre(a) - grid.Centre(b)) < exclusion_frames) continue;
    values.push_back(cells.at(a, b));
  }
  std::sort(values.begin(), values.end());
  return values;
}

// The cells along the cheapest warp between every two non-overlapping occurrences of one
// movement.
std::vector<double> AlignedCells(ColumnCandidate& candidate,
                                 const std::vector<motif::TruthOccurrence>& occurrences) {
  const ColumnMatrix& cells = candidate.matrix();
  std::vector<double> values;
  for (size_t x = 0; x < occurrences.size(); ++x) {
    for (size_t y = x + 1; y < occurrences.size(); ++y) {
      const Span a{occurrences[x].start, occurrences[x].end};
      const Span b{occurrences[y].start, occurrences[y].end};
      if (occurrences[x].movement != occurrences[y].movement || a.Overlaps(b)) continue;
      const std::vector<uint32_t> ca = candidate.grid().Columns(a);
      const std::vector<uint32_t> cb = candidate.grid().Columns(b);
      auto cost = [&](uint32_t i, uint32_t j) {
        return static_cast<double>(cells.at(ca[i], cb[j]));
      };
      for (auto [i, j] : motif::testing::WarpPath(static_cast<uint32_t>(ca.size()),
                                                  static_cast<uint32_t>(cb.size()), cost)) {
        values.push_back(cost(i, j));
      }
    }
  }
  return values;
}

ColumnStats Distribution(ColumnCandidate& candidate,
                         const std::vector<motif::TruthOccurrence>& occurrences,
                         double exclusion_frames, int pairs, motif::SplitMix64* random) {
  ColumnStats stats;
  const std::vector<double> random_cells =
      RandomColumnPairs(candidate, exclusion_frames, pairs, random);
  if (random_cells.empty()) return stats;
  stats.present = true;
  stats.random_q05 = Quantile(random_cells, 0.05);
  stats.random_q10 = Quantile(random_cells, 0.10);
  stats.random_q50 = Quantile(random_cells, 0.50);
  std::vector<double> aligned = AlignedCells(candidate, occurrences);
  stats.aligned_cells = aligned.size();
  if (aligned.empty()) return stats;
  std::vector<double> percentiles;
  uint64_t within = 0;
  for (double value : aligned) {
    const auto below = std::lower_bound(random_cells.begin(), random_cells.end(), value);
    percentiles.push_back(static_cast<double>(below - random_cells.begin()) /
                          static_cast<double>(random_cells.size()));
    within += value <= stats.random_q10 ? 1 : 0;
  }
  std::sort(aligned.begin(), aligned.end());
  std::sort(percentiles.begin(), percentiles.end());
  stats.aligned_median = Quantile(aligned, 0.5);
  stats.aligned_pct_median = Quantile(percentiles, 0.5);
  stats.aligned_pct_p90 = Quantile(percentiles, 0.9);
  stats.aligned_within_q10 = static_cast<double>(within) / static_cast<double>(aligned.size());
  return stats;
}

// The queries that can be answered, with their stretches.
struct Workload {
  std::vector<motif::testing::Query> queries;
  std::vector<std::vector<Stretch>> stretches;
  uint32_t unanswerable = 0;
  uint64_t stretch_count = 0;
};

Workload BuildWorkload(const std::vector<motif::TruthOccurrence>& occurrences, uint64_t clip_frames,
                       const motif::testing::StretchOptions& options) {
  Workload work;
  for (motif::testing::Query& query : motif::testing::BuildQueries(occurrences)) {
    std::vector<Stretch> stretches = motif::testing::BuildStretches(query, clip_frames, options);
    if (!motif::testing::HasPositive(stretches)) {
      ++work.unanswerable;
      continue;
    }
    work.stretch_count += stretches.size();
    work.queries.push_back(std::move(query));
    work.stretches.push_back(std::move(stretches));
  }
  return work;
}

std::vector<std::pair<Span, Span>> TimingPairs(uint64_t clip_frames, double fps, int count,
                                               motif::SplitMix64* random) {
  const uint64_t length =
      std::max<uint64_t>(2, std::min<uint64_t>(std::lround(fps), clip_frames / 2));
  std::vector<std::pair<Span, Span>> pairs;
  for (int idx = 0; idx < count; ++idx) {
    const uint64_t a = random->Below(clip_frames - length + 1);
    const uint64_t b = random->Below(clip_frames - length + 1);
    pairs.push_back({Span{a, a + length}, Span{b, b + length}});
  }
  return pairs;
}

// The largest difference between quat_dtw's warp (every frame, on the frame grid of 1) and
// engine/cluster's MeanWarpedDistance on a few short stretches: the two must agree.
double CheckAgainstClustering(const ClipData& data, motif::SplitMix64* random) {
  ColumnGrid grid;
  grid.count = static_cast<uint32_t>(data.info.frame_count);
  grid.samples = motif::testing::kMaxWarpColumns;
  const motif::testing::QuatColumns quat(*data.features, data.info.first_frame, grid,
                                         data.info.frame_count);
  ColumnCandidate candidate("check", "", "", grid,
                            std::shared_ptr<const ColumnDistance>(&quat, [](const auto*) {}), true,
                            0, 0);
  double worst = 0;
  const auto pairs = TimingPairs(data.info.frame_count, 24, 20, random);
  for (const auto& [a, b] : pairs) {
    const double mine = candidate.Evaluate(a, b);
    const uint64_t first = data.info.first_frame;
    const double engine = motif::MeanWarpedDistance(*data.features, first + a.start, first + a.end,
                                                    first + b.start, first + b.end);
    worst = std::max(worst, std::abs(mine - engine));
  }
  return worst;
}

}  // namespace

namespace {

struct Row {
  std::string take;
  const Candidate* candidate = nullptr;
  motif::testing::RankingScore score;
  Timing timing;
  ColumnStats stats;
  double seconds = 0;
};

void PrintHeader() {
  std::printf("%-12s %7s %6s %6s %6s %6s %9s %10s %9s %9s %9s %9s %9s %8s %8s %7s\n", "candidate",
              "queries", "1-NN", "part", "AUC", "AUC/q", "pair_us", "colpair_ns", "column_ns",
              "frame_ns", "rand_q10", "rand_q50", "align_med", "pct_med", "pct_p90", "in_q10");
}

void PrintRow(const Row& row) {
  const auto& s = row.score;
  const double queries = std::max(1u, s.queries);
  std::printf("%-12s %7u %6.3f %6.3f %6.3f %6.3f %9.2f %10.1f %9.1f %9.1f",
              row.candidate->name().c_str(), s.queries, s.hits / queries,
              s.partial_misses / queries, s.auc_pooled, s.auc_query_mean, row.timing.pair_ns / 1000,
              row.timing.column_pair_ns, row.timing.column_ns, row.timing.frame_ns);
  const ColumnStats& c = row.stats;
  if (c.present) {
    std::printf(" %9.4f %9.4f %9.4f %8.3f %8.3f %7.3f", c.random_q10, c.random_q50,
                c.aligned_median, c.aligned_pct_median, c.aligned_pct_p90, c.aligned_within_q10);
  } else {
    std::printf(" %9s %9s %9s %8s %8s %7s", "-", "-", "-", "-", "-", "-");
  }
  const std::string note = row.candidate->Note();
  std::printf("%s%s\n", note.empty() ? "" : "  ", note.c_str());
}

const char* kRowHeader =
    "take\tcandidate\tqueries\thits\tpartial_misses\tauc_pooled\tauc_query\tauc_queries\tpair_"
    "ns\tcolumn_pair_ns\t"
    "column_ns\tframe_ns\tstats\trandom_q05\trandom_q10\trandom_q50\taligned_median\taligned_pct_"
    "median\t"
    "aligned_pct_p90\taligned_within_q10\taligned_cells\tseconds\tcolumn\tproperties\tnote\n";

void WriteRow(std::ofstream& out, const Row& row) {
  const auto& s = row.score;
  const auto& c = row.stats;
  out << row.take << '\t' << row.candidate->name() << '\t' << s.queries << '\t' << s.hits << '\t'
      << s.partial_misses << '\t' << s.auc_pooled << '\t' << s.auc_query_mean << '\t'
      << s.auc_queries << '\t' << row.timing.pair_ns << '\t' << row.timing.column_pair_ns << '\t'
      << row.timing.column_ns << '\t' << row.timing.frame_ns << '\t' << (c.present ? 1 : 0) << '\t'
      << c.random_q05 << '\t' << c.random_q10 << '\t' << c.random_q50 << '\t' << c.aligned_median
      << '\t' << c.aligned_pct_median << '\t' << c.aligned_pct_p90 << '\t' << c.aligned_within_q10
      << '\t' << c.aligned_cells << '\t' << row.seconds << '\t' << row.candidate->column() << '\t'
      << row.candidate->properties() << '\t' << row.candidate->Note() << '\n';
}

// Opens `path` for appending, with the header if it is new.
std::optional<std::ofstream> OpenAppend(const std::string& path, const char* header) {
  if (path.empty()) return std::nullopt;
  const bool fresh = !std::ifstream(path).good();
  std::ofstream out(path, std::ios::app);
  if (fresh) out << header;
  return out;
}

// 1-NN hits per movement of the queries.
void WriteMovements(std::ofstream* out, const std::string& take, const Candidate& candidate,
                    const Workload& work, const std::vector<std::vector<float>>& distances) {
  std::map<std::string, std::pair<int, int>> counts;  // movement -> (queries, hits)
  for (size_t query = 0; query < work.queries.size(); ++query) {
    auto& [queries, hits] = counts[work.queries[query].movement];
    ++queries;
    hits += motif::testing::NearestIsPositive(work.stretches[query], distances[query]) ? 1 : 0;
  }
  for (const auto& [movement, count] : counts) {
    *out << take << '\t' << candidate.name() << '\t' << movement << '\t' << count.first << '\t'
         << count.second << '\n';
  }
}

Row RunCandidate(Candidate& candidate, const std::string& take, const Workload& work,
                 const ClipData& data, const std::vector<motif::TruthOccurrence>& occurrences,
                 const motif::testing::ExperimentArgs& args,
                 std::vector<std::vector<float>>* distances) {
  Row row;
  row.take = take;
  row.candidate = &candidate;
  const auto started = std::chrono::steady_clock::now();
  distances->clear();
  for (size_t query = 0; query < work.queries.size(); ++query) {
    distances->push_back(candidate.Rank(work.queries[query].span, work.stretches[query]));
  }
  row.seconds = Seconds(started);
  row.score = motif::testing::ScoreRanking(work.stretches, *distances);
  motif::SplitMix64 random(static_cast<uint64_t>(args.number("seed", 1)));
  if (auto* columns = dynamic_cast<ColumnCandidate*>(&candidate)) {
    row.stats =
        Distribution(*columns, occurrences, args.number("exclusion", 0.25) * data.reader->fps(),
                     static_cast<int>(args.number("random_pairs", 20000)), &random);
  }
  candidate.Release();
  const auto pairs = TimingPairs(data.info.frame_count, data.reader->fps(),
                                 static_cast<int>(args.number("timing_pairs", 200)), &random);
  row.timing = candidate.Time(pairs, static_cast<int>(args.number("repeats", 5)), &random);
  return row;
}

bool Wanted(const motif::testing::ExperimentArgs& args, const std::string& name) {
  if (!args.has("candidates")) return true;
  std::string list = ",";
  list.append(args.text("candidates")).append(",");
  std::string item = ",";
  item.append(name).append(",");
  return list.find(item) != std::string::npos;
}

// The clip to study: clip=NAME, else the first clip of the truth file that the archive has.
motif::Result<size_t> ChooseClip(const motif::FrameFileReader& reader,
                                 const std::vector<motif::TruthOccurrence>& truth,
                                 const std::string& wanted) {
  for (const motif::TruthOccurrence& occurrence : truth) {
    if (!wanted.empty() && occurrence.clip != wanted) continue;
    for (size_t idx = 0; idx < reader.clips().size(); ++idx) {
      if (reader.clips()[idx].name == occurrence.clip) return idx;
    }
  }
  return motif::Status::NotFound("no clip of the truth file is in the archive");
}

StudyOptions OptionsFrom(const motif::testing::ExperimentArgs& args) {
  StudyOptions options;
  options.frame_grid = std::max(1u, static_cast<uint32_t>(args.number("frame_grid", 2)));
  options.samples = std::clamp(static_cast<uint32_t>(args.number("samples", 32)), 2u,
                               motif::testing::kMaxWarpColumns);
  options.word_stride = std::max(1u, static_cast<uint32_t>(args.number("word_stride", 4)));
  options.word_frames =
      std::clamp(static_cast<uint32_t>(args.number("word_frames", 16)), 2u, motif::kMaxWordFrames);
  options.mp_window = args.number("mp_window", 0.33);
  options.mp_floor = args.number("mp_floor", 0.01);
  options.warp_band = args.number("warp_band", 0);
  options.repeats = std::max(1, static_cast<int>(args.number("repeats", 5)));
  return options;
}

motif::testing::StretchOptions StretchOptionsFrom(const motif::testing::ExperimentArgs& args) {
  motif::testing::StretchOptions options;
  options.start_stride = std::max(1u, static_cast<uint32_t>(args.number("start_stride", 4)));
  options.min_scale = args.number("min_scale", 0.5);
  options.max_scale = args.number("max_scale", 2.0);
  options.scale_steps = std::max(1u, static_cast<uint32_t>(args.number("scale_steps", 9)));
  return options;
}

motif::Status Run(const std::string& archive_path, const std::string& truth_path,
                  const motif::testing::ExperimentArgs& args) {
  MOTIF_ASSIGN_OR_RETURN(const motif::testing::StudyArchive archive,
                         motif::testing::OpenStudyArchive(archive_path));
  MOTIF_ASSIGN_OR_RETURN(const std::vector<motif::TruthOccurrence> truth,
                         motif::ReadTruthOccurrences(truth_path));
  MOTIF_ASSIGN_OR_RETURN(const size_t clip_idx,
                         ChooseClip(*archive.reader, truth, args.text("clip")));
  const StudyOptions options = OptionsFrom(args);
  MOTIF_ASSIGN_OR_RETURN(const ClipData data, LoadClip(archive, clip_idx, options.repeats));
  const std::string take = data.info.name;
  std::vector<motif::TruthOccurrence> occurrences;
  for (const auto& occurrence : truth) {
    if (occurrence.clip == take) occurrences.push_back(occurrence);
  }
  const Workload work = BuildWorkload(occurrences, data.info.frame_count, StretchOptionsFrom(args));
  motif::SplitMix64 check_random(static_cast<uint64_t>(args.number("seed", 1)));
  std::printf(
      "# %s: %llu frames at %.0f fps, %zu occurrences, %zu queries (%u cannot be "
      "answered), %.0f stretches a query; %s\n# check: quat_dtw against "
      "MeanWarpedDistance, largest difference %.3g\n",
      take.c_str(), static_cast<unsigned long long>(data.info.frame_count), data.reader->fps(),
      occurrences.size(), work.queries.size(), work.unanswerable,
      work.queries.empty() ? 0.0 : static_cast<double>(work.stretch_count) / work.queries.size(),
      data.body->Describe(data.reader->skeleton()).c_str(),
      CheckAgainstClustering(data, &check_random));
  CandidateSet set;
  set.band = options.warp_band;
  AddBodyCandidates(data, options, &set);
  MOTIF_ASSIGN_OR_RETURN(ClipWordColumns words, LoadWords(data, options));
  const motif::Status embedded =
      AddWordCandidates(data, options, args.text("embedding"), &words, &set);
  if (!embedded.ok()) std::printf("# embedding left out: %s\n", embedded.ToString().c_str());
  AddPartCandidates(*data.body, &set);
  auto rows_out = OpenAppend(args.text("out"), kRowHeader);
  auto movements_out =
      OpenAppend(args.text("movements_out"), "take\tcandidate\tmovement\tqueries\thits\n");
  PrintHeader();
  std::vector<std::vector<float>> distances;
  for (Candidate* candidate : set.order) {
    if (!Wanted(args, candidate->name())) continue;
    const Row row = RunCandidate(*candidate, take, work, data, occurrences, args, &distances);
    PrintRow(row);
    std::fflush(stdout);
    if (rows_out) WriteRow(*rows_out, row);
    if (movements_out) WriteMovements(&*movements_out, take, *candidate, work, distances);
  }
  return motif::Status::Ok();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: distance_study ARCHIVE.mfs TRUTH.tsv [clip=NAME] [candidates=a,b,...] "
                 "[embedding=FILE.mwe] [frame_grid=2] [samples=32] [word_frames=16] "
                 "[word_stride=4] "
                 "[start_stride=4] [min_scale=0.5] [max_scale=2] [scale_steps=9] "
                 "[mp_window=0.33] [mp_floor=0.01] [warp_band=0] [exclusion=0.25] "
                 "[random_pairs=20000] "
                 "[timing_pairs=200] [repeats=5] [seed=1] [out=ROWS.tsv] "
                 "[movements_out=MOVEMENTS.tsv]\n";
    return 2;
  }
  const motif::testing::ExperimentArgs args(argc - 2, argv + 2);
  const motif::Status status = Run(argv[1], argv[2], args);
  if (!status.ok()) {
    std::cerr << status.ToString() << "\n";
    return 1;
  }
  return 0;
}
