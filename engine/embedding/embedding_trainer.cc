#include "engine/embedding/embedding_trainer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "common/split_mix64.h"

namespace motif {
namespace {

// Rows per chunk of a batch: the unit of parallel work, fixed so that the gradient sums do not
// depend on the thread count.
constexpr size_t kChunkRows = 32;
constexpr double kAdamBeta1 = 0.9;
constexpr double kAdamBeta2 = 0.999;
constexpr double kAdamEpsilon = 1e-8;

using Matrix = EmbeddingNet::Matrix;

uint64_t EpochSeed(uint64_t seed, uint64_t epoch) {
  SplitMix64 mix(seed ^ (epoch * 0xd1b54a32d192ed03ull) ^ 0x747269706c6574ull);  // "triplet"
  return mix.Next();
}

template <typename Body>
void ForEachChunk(tbb::task_arena& arena, size_t chunks, const Body& body) {
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1),
                      [&](const tbb::blocked_range<size_t>& range) {
                        for (size_t chunk = range.begin(); chunk != range.end(); ++chunk)
                          body(chunk);
                      });
  });
}

}  // namespace

Status ValidateEmbeddingTrainOptions(const EmbeddingTrainOptions& options) {
  if (options.batch_triplets == 0)
    return Status::InvalidArgument("training: batch_triplets must be >= 1");
  if (!(options.learning_rate > 0) || !std::isfinite(options.learning_rate)) {
    return Status::InvalidArgument("training: learning_rate must be positive");
  }
  if (!(options.margin > 0) || !std::isfinite(options.margin)) {
    return Status::InvalidArgument("training: margin must be positive");
  }
  if (options.temporal_positives + options.dtw_positives == 0) {
    return Status::InvalidArgument("training: at least one kind of positive is needed");
  }
  if (options.far_words == 0) return Status::InvalidArgument("training: far_words must be >= 1");
  return ValidateEmbeddingNetShape(options.shape);
}

Result<EmbeddingTrainer> EmbeddingTrainer::Create(
    const WordPool& pool, std::vector<std::vector<WordNeighbour>> neighbours,
    const EmbeddingTrainOptions& options) {
  EmbeddingTrainOptions resolved = options;
  resolved.shape.frames = pool.word_frames();
  resolved.shape.input_channels = pool.input_channels();
  MOTIF_RETURN_IF_ERROR(ValidateEmbeddingTrainOptions(resolved));
  if (neighbours.size() != pool.size()) {
    return Status::InvalidArgument("training: " + std::to_string(neighbours.size()) +
                                   " neighbour lists for " + std::to_string(pool.size()) +
                                   " words");
  }
  EmbeddingTrainer trainer(pool, resolved);
  trainer.neighbours_ = std::move(neighbours);
  for (uint64_t word = 0; word < pool.size(); ++word) {
    if (!pool.held_out(word)) trainer.train_words_.push_back(static_cast<uint32_t>(word));
  }
  if (trainer.train_words_.empty()) return Status::InvalidArgument("training: no training word");
  trainer.positives_.resize(pool.size());
  for (uint32_t word : trainer.train_words_) {
    trainer.positives_[word] = trainer.Positives(word, /*train=*/true);
  }

  // Standardisation from the training words' inputs (every frame), summed in double in order.
  const uint32_t channels = pool.input_channels();
  const uint32_t frames = pool.word_frames();
  std::vector<double> sum(channels, 0.0);
  std::vector<double> sum2(channels, 0.0);
  std::vector<float> input(static_cast<size_t>(frames) * channels);
  for (uint32_t word : trainer.train_words_) {
    pool.EncodeInput(word, 0, input.data());
    for (uint32_t frame = 0; frame < frames; ++frame) {
      for (uint32_t channel = 0; channel < channels; ++channel) {
        const double value = input[frame * channels + channel];
        sum[channel] += value;
        sum2[channel] += value * value;
      }
    }
  }
  const double count = static_cast<double>(trainer.train_words_.size()) * frames;
  std::vector<float> mean(channels);
  std::vector<float> deviation(channels);
  for (uint32_t channel = 0; channel < channels; ++channel) {
    const double m = sum[channel] / count;
    mean[channel] = static_cast<float>(m);
    deviation[channel] =
        static_cast<float>(std::sqrt(std::max(0.0, sum2[channel] / count - m * m)));
  }
  trainer.initial_ = EmbeddingNet(resolved.shape);
  trainer.initial_.Initialize(resolved.seed);
  trainer.initial_.SetInputStandardisation(std::move(mean), std::move(deviation));
  return trainer;
}

std::vector<uint32_t> EmbeddingTrainer::Positives(uint64_t word, bool train) const {
  const WordPool& pool = *pool_;
  std::vector<uint32_t> positives;
  const PoolClip& clip = pool.clips()[pool.clip_of(word)];
  const int64_t index = static_cast<int64_t>(pool.index_in_clip(word));
  const int64_t count = static_cast<int64_t>(clip.word_count);
  // Temporal: offsets -o, +o, -(o+1), +(o+1), ... (o = overlap_words), the first z in the clip.
  const int64_t overlap = pool.overlap_words();
  for (int64_t step = overlap; positives.size() < options_.temporal_positives; ++step) {
    if (index - step < 0 && index + step >= count) break;
    for (int64_t other : {index - step, index + step}) {
      if (other >= 0 && other < count && positives.size() < options_.temporal_positives) {
        positives.push_back(static_cast<uint32_t>(clip.first_word + other));
      }
    }
  }
  uint32_t from_dtw = 0;
  for (const WordNeighbour& neighbour : neighbours_[word]) {
    if (from_dtw == options_.dtw_positives) break;
    if (train && pool.held_out(neighbour.word)) continue;
    if (std::find(positives.begin(), positives.end(), neighbour.word) == positives.end()) {
      positives.push_back(neighbour.word);
    }
    ++from_dtw;
  }
  return positives;
}

bool EmbeddingTrainer::ValidNegative(uint64_t anchor, uint64_t other) const {
  const WordPool& pool = *pool_;
  if (pool.clip_of(anchor) != pool.clip_of(other)) return true;
  const uint64_t a = pool.index_in_clip(anchor);
  const uint64_t b = pool.index_in_clip(other);
  return (a > b ? a - b : b - a) >= options_.far_words;
}

uint32_t EmbeddingTrainer::DrawNegative(uint64_t anchor, bool train, SplitMix64* random) const {
  const WordPool& pool = *pool_;
  const PoolClip& clip = pool.clips()[pool.clip_of(anchor)];
  const uint64_t index = pool.index_in_clip(anchor);
  // Same-clip words at least far_words away: [0, index - far] and [index + far, count).
  const uint64_t far = options_.far_words;
  const uint64_t below = index >= far ? index - far + 1 : 0;
  const uint64_t above = index + far < clip.word_count ? clip.word_count - (index + far) : 0;
  const bool same_clip = (below + above > 0) && (random->Next() & 1);
  if (same_clip) {
    const uint64_t pick = random->Below(below + above);
    return static_cast<uint32_t>(clip.first_word +
                                 (pick < below ? pick : index + far + (pick - below)));
  }
  const bool other_clips =
      train ? train_words_.size() > clip.word_count : pool.size() > clip.word_count;
  if (!other_clips) {  // a pool of one clip: a far word of it if any, else any other word
    if (below + above > 0) {
      const uint64_t pick = random->Below(below + above);
      return static_cast<uint32_t>(clip.first_word +
                                   (pick < below ? pick : index + far + (pick - below)));
    }
    return static_cast<uint32_t>(anchor == 0 ? std::min<uint64_t>(1, pool.size() - 1) : 0);
  }
  for (;;) {
    const uint32_t other = train ? train_words_[random->Below(train_words_.size())]
                                 : static_cast<uint32_t>(random->Below(pool.size()));
    if (pool.clip_of(other) != pool.clip_of(anchor)) return other;
  }
}

TrainingState EmbeddingTrainer::InitialState() const {
  TrainingState state;
  state.parameters = initial_.parameters();
  state.adam_m.assign(state.parameters.size(), 0.0f);
  state.adam_v.assign(state.parameters.size(), 0.0f);
  return state;
}

EmbeddingNet EmbeddingTrainer::NetOf(const TrainingState& state) const {
  EmbeddingNet net = initial_;
  net.mutable_parameters() = state.parameters;
  return net;
}

// One batch's rows and buffers, reused from batch to batch, and the arena its chunks run in.
struct EmbeddingTrainer::BatchWork {
  BatchWork(int threads, size_t parameter_count)
      : arena(threads > 0 ? threads : tbb::task_arena::automatic), gradient(parameter_count) {}

  tbb::task_arena arena;
  // Rows: anchors [0, count), positives [count, 2 count), negatives [2 count, 3 count).
  std::vector<BatchRow> rows;
  Matrix input;
  Matrix embeddings;
  Matrix d_embeddings;
  std::vector<EmbeddingNet::Workspace> workspaces;  // per chunk of kChunkRows rows
  std::vector<std::vector<float>> chunk_gradients;
  std::vector<float> gradient;  // the chunks' gradients summed in chunk order
};

std::vector<uint32_t> EmbeddingTrainer::TrainingAnchors() const {
  std::vector<uint32_t> anchors;
  for (uint32_t word : train_words_) {
    if (!positives_[word].empty()) anchors.push_back(word);
  }
  return anchors;
}

void EmbeddingTrainer::DrawBatchRows(const std::vector<uint32_t>& order, size_t first, size_t count,
                                     SplitMix64* random, BatchWork* work) const {
  const WordPool& pool = *pool_;
  std::vector<BatchRow>& rows = work->rows;
  rows.assign(3 * count, BatchRow{0, 0});
  for (size_t idx = 0; idx < count; ++idx) {
    const uint32_t anchor = order[first + idx];
    const std::vector<uint32_t>& positives = positives_[anchor];
    rows[idx] = {anchor, 0};
    rows[count + idx] = {positives[random->Below(positives.size())],
                         static_cast<uint32_t>(random->Below(pool.versions()))};
    rows[2 * count + idx] = {DrawNegative(anchor, /*train=*/true, random),
                             static_cast<uint32_t>(random->Below(pool.versions()))};
  }
}

void EmbeddingTrainer::EmbedBatch(const EmbeddingNet& net, BatchWork* work) const {
  const WordPool& pool = *pool_;
  const std::vector<BatchRow>& rows = work->rows;
  const size_t row_count = rows.size();
  const size_t chunks = (row_count + kChunkRows - 1) / kChunkRows;
  work->input.resize(static_cast<Eigen::Index>(row_count),
                     static_cast<Eigen::Index>(options_.shape.input_size()));
  work->embeddings.resize(static_cast<Eigen::Index>(row_count), options_.shape.embedding_dims);
  work->workspaces.resize(chunks);
  ForEachChunk(work->arena, chunks, [&](size_t chunk) {
    const size_t begin = chunk * kChunkRows;
    const size_t end = std::min(row_count, begin + kChunkRows);
    for (size_t row = begin; row < end; ++row) {
      pool.EncodeInput(rows[row].word, rows[row].version,
                       work->input.row(static_cast<Eigen::Index>(row)).data());
    }
    net.Forward(work->input.middleRows(static_cast<Eigen::Index>(begin),
                                       static_cast<Eigen::Index>(end - begin)),
                &work->workspaces[chunk]);
    work->embeddings.middleRows(static_cast<Eigen::Index>(begin),
                                static_cast<Eigen::Index>(end - begin)) =
        work->workspaces[chunk].embeddings;
  });
}

void EmbeddingTrainer::TripletLossGradient(size_t count, BatchWork* work, double* loss_sum,
                                           uint64_t* active) const {
  const Matrix& embeddings = work->embeddings;
  const std::vector<BatchRow>& rows = work->rows;
  const float margin = static_cast<float>(options_.margin);
  Matrix& d_embeddings = work->d_embeddings;
  d_embeddings.setZero(static_cast<Eigen::Index>(rows.size()), options_.shape.embedding_dims);
  const float scale = 1.0f / static_cast<float>(count);
  for (size_t idx = 0; idx < count; ++idx) {
    const auto a = embeddings.row(static_cast<Eigen::Index>(idx));
    const auto p = embeddings.row(static_cast<Eigen::Index>(count + idx));
    const float positive = (a - p).squaredNorm();
    size_t negative_row = 2 * count + idx;
    float negative = (a - embeddings.row(static_cast<Eigen::Index>(negative_row))).squaredNorm();
    if (options_.mine_semi_hard) {
      float best = std::numeric_limits<float>::infinity();
      for (size_t other = 0; other < count; ++other) {
        const size_t row = 2 * count + other;
        if (!ValidNegative(rows[idx].word, rows[row].word)) continue;
        const float candidate = (a - embeddings.row(static_cast<Eigen::Index>(row))).squaredNorm();
        if (candidate > positive && candidate < positive + margin && candidate < best) {
          best = candidate;
          negative_row = row;
        }
      }
      if (best < std::numeric_limits<float>::infinity()) negative = best;
    }
    const float loss = positive - negative + margin;
    if (loss <= 0) continue;
    *loss_sum += loss;
    ++*active;
    const auto n = embeddings.row(static_cast<Eigen::Index>(negative_row));
    // d/da = 2 (n - p), d/dp = 2 (p - a), d/dn = 2 (a - n); times 1 / count (the mean).
    d_embeddings.row(static_cast<Eigen::Index>(idx)) += 2.0f * scale * (n - p);
    d_embeddings.row(static_cast<Eigen::Index>(count + idx)) += 2.0f * scale * (p - a);
    d_embeddings.row(static_cast<Eigen::Index>(negative_row)) += 2.0f * scale * (a - n);
  }
}

void EmbeddingTrainer::BatchGradient(const EmbeddingNet& net, BatchWork* work) const {
  const size_t parameter_count = options_.shape.parameter_count();
  const size_t row_count = work->rows.size();
  const size_t chunks = (row_count + kChunkRows - 1) / kChunkRows;
  work->chunk_gradients.resize(chunks);
  ForEachChunk(work->arena, chunks, [&](size_t chunk) {
    const size_t begin = chunk * kChunkRows;
    const size_t end = std::min(row_count, begin + kChunkRows);
    work->chunk_gradients[chunk].assign(parameter_count, 0.0f);
    net.Backward(work->d_embeddings.middleRows(static_cast<Eigen::Index>(begin),
                                               static_cast<Eigen::Index>(end - begin)),
                 &work->workspaces[chunk], work->chunk_gradients[chunk].data());
  });
  std::vector<float>& gradient = work->gradient;
  std::fill(gradient.begin(), gradient.end(), 0.0f);
  for (size_t chunk = 0; chunk < chunks; ++chunk) {
    for (size_t idx = 0; idx < parameter_count; ++idx)
      gradient[idx] += work->chunk_gradients[chunk][idx];
  }
}

void EmbeddingTrainer::AdamStep(const std::vector<float>& gradient, TrainingState* state,
                                EmbeddingNet* net) const {
  ++state->adam_steps;
  const double correction1 = 1.0 - std::pow(kAdamBeta1, static_cast<double>(state->adam_steps));
  const double correction2 = 1.0 - std::pow(kAdamBeta2, static_cast<double>(state->adam_steps));
  const double step = options_.learning_rate * std::sqrt(correction2) / correction1;
  std::vector<float>& parameters = net->mutable_parameters();
  for (size_t idx = 0; idx < gradient.size(); ++idx) {
    const float g = gradient[idx];
    state->adam_m[idx] = static_cast<float>(kAdamBeta1 * state->adam_m[idx] + (1 - kAdamBeta1) * g);
    state->adam_v[idx] =
        static_cast<float>(kAdamBeta2 * state->adam_v[idx] + (1 - kAdamBeta2) * g * g);
    parameters[idx] -=
        static_cast<float>(step * state->adam_m[idx] /
                           (std::sqrt(static_cast<double>(state->adam_v[idx])) + kAdamEpsilon));
  }
}

Status EmbeddingTrainer::Train(
    TrainingState* state, const std::function<Status(const TrainingState&)>& checkpoint) const {
  const size_t parameter_count = options_.shape.parameter_count();
  if (state->parameters.size() != parameter_count || state->adam_m.size() != parameter_count ||
      state->adam_v.size() != parameter_count) {
    return Status::InvalidArgument(
        "training: a state of " + std::to_string(state->parameters.size()) +
        " parameters for a network of " + std::to_string(parameter_count));
  }
  const uint32_t batch_size = options_.batch_triplets;
  const std::vector<uint32_t> anchors = TrainingAnchors();
  if (anchors.empty()) return Status::InvalidArgument("training: no anchor has a positive");
  const uint64_t batches_per_epoch = (anchors.size() + batch_size - 1) / batch_size;
  const uint64_t total_batches = batches_per_epoch * options_.epochs;

  EmbeddingNet net = NetOf(*state);
  BatchWork work(options_.threads, parameter_count);
  for (uint32_t epoch = state->epochs_done; epoch < options_.epochs; ++epoch) {
    // The epoch's seed shuffles the anchors, then draws every batch's positives and negatives.
    SplitMix64 random(EpochSeed(options_.seed, epoch));
    std::vector<uint32_t> order = anchors;
    for (size_t idx = order.size() - 1; idx > 0; --idx) {
      std::swap(order[idx], order[random.Below(idx + 1)]);
    }
    double loss_sum = 0;
    uint64_t active = 0;
    for (uint64_t batch = 0; batch < batches_per_epoch; ++batch) {
      const size_t first = batch * batch_size;
      const size_t count = std::min<size_t>(batch_size, order.size() - first);
      DrawBatchRows(order, first, count, &random, &work);
      EmbedBatch(net, &work);
      // The loss, with in-batch semi-hard negatives, and its gradient per embedding row.
      TripletLossGradient(count, &work, &loss_sum, &active);
      BatchGradient(net, &work);
      AdamStep(work.gradient, state, &net);
      if (options_.progress)
        options_.progress(epoch * batches_per_epoch + batch + 1, total_batches);
    }
    state->parameters = net.parameters();
    state->epochs_done = epoch + 1;
    state->epoch_loss.push_back(loss_sum / static_cast<double>(anchors.size()));
    state->epoch_active.push_back(static_cast<double>(active) /
                                  static_cast<double>(anchors.size()));
    if (checkpoint) MOTIF_RETURN_IF_ERROR(checkpoint(*state));
  }
  return Status::Ok();
}

RowMatrixXf EmbeddingTrainer::EmbedPool(const EmbeddingNet& net) const {
  const WordPool& pool = *pool_;
  const uint64_t n = pool.size();
  const size_t input_size = net.shape().input_size();
  RowMatrixXf embeddings(static_cast<Eigen::Index>(n), net.shape().embedding_dims);
  tbb::task_arena arena(options_.threads > 0 ? options_.threads : tbb::task_arena::automatic);
  const size_t chunks = (n + kChunkRows - 1) / kChunkRows;
  ForEachChunk(arena, chunks, [&](size_t chunk) {
    const size_t begin = chunk * kChunkRows;
    const size_t end = std::min<size_t>(n, begin + kChunkRows);
    Matrix input(static_cast<Eigen::Index>(end - begin), static_cast<Eigen::Index>(input_size));
    for (size_t word = begin; word < end; ++word) {
      pool.EncodeInput(word, 0, input.row(static_cast<Eigen::Index>(word - begin)).data());
    }
    EmbeddingNet::Workspace workspace;
    net.Forward(input, &workspace);
    embeddings.middleRows(static_cast<Eigen::Index>(begin),
                          static_cast<Eigen::Index>(end - begin)) = workspace.embeddings;
  });
  return embeddings;
}

TripletAccuracy EmbeddingTrainer::HeldOutAccuracy(const EmbeddingNet& trained) const {
  const WordPool& pool = *pool_;
  struct Triplet {
    uint32_t anchor, positive, negative;
  };
  std::vector<Triplet> triplets;
  SplitMix64 random(options_.seed ^ 0x68656c646f75742eull);
  for (uint64_t word = 0; word < pool.size(); ++word) {
    if (!pool.held_out(word)) continue;
    for (uint32_t positive : Positives(word, /*train=*/false)) {
      triplets.push_back(
          {static_cast<uint32_t>(word), positive, DrawNegative(word, /*train=*/false, &random)});
    }
  }
  TripletAccuracy accuracy;
  accuracy.triplets = triplets.size();
  if (triplets.empty()) return accuracy;
  // Raw: the standardised inputs (the trained network's standardisation, which is the initial
  // one: it is fixed before training), of the words the triplets use only.
  const uint32_t channels = pool.input_channels();
  const size_t input_size = static_cast<size_t>(pool.word_frames()) * channels;
  std::unordered_map<uint32_t, size_t> slot;
  for (const Triplet& t : triplets) {
    for (uint32_t word : {t.anchor, t.positive, t.negative}) slot.emplace(word, slot.size());
  }
  std::vector<float> raw(slot.size() * input_size);
  for (const auto& [word, index] : slot) {
    float* out = &raw[index * input_size];
    pool.EncodeInput(word, 0, out);
    for (size_t value = 0; value < input_size; ++value) {
      const size_t channel = value % channels;
      out[value] = (out[value] - trained.input_mean()[channel]) / trained.input_std()[channel];
    }
  }
  auto raw_distance = [&](uint32_t a, uint32_t b) {
    const float* x = &raw[slot.at(a) * input_size];
    const float* y = &raw[slot.at(b) * input_size];
    double sum = 0;
    for (size_t value = 0; value < input_size; ++value) {
      const double delta = x[value] - y[value];
      sum += delta * delta;
    }
    return sum;
  };
  const RowMatrixXf untrained = EmbedPool(initial_);
  const RowMatrixXf embedded = EmbedPool(trained);
  uint64_t raw_right = 0;
  uint64_t untrained_right = 0;
  uint64_t trained_right = 0;
  for (const Triplet& t : triplets) {
    raw_right += raw_distance(t.anchor, t.positive) < raw_distance(t.anchor, t.negative);
    untrained_right += (untrained.row(t.anchor) - untrained.row(t.positive)).squaredNorm() <
                       (untrained.row(t.anchor) - untrained.row(t.negative)).squaredNorm();
    trained_right += (embedded.row(t.anchor) - embedded.row(t.positive)).squaredNorm() <
                     (embedded.row(t.anchor) - embedded.row(t.negative)).squaredNorm();
  }
  const double total = static_cast<double>(triplets.size());
  accuracy.raw = raw_right / total;
  accuracy.untrained = untrained_right / total;
  accuracy.trained = trained_right / total;
  return accuracy;
}

}  // namespace motif
