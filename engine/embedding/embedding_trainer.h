// EmbeddingTrainer: trains the word embedding (embedding_net.h) with a triplet loss (Schroff et
// al. 2015, FaceNet; Aristidou et al. 2018, section 4.2) on a WordPool:
//
//   loss(a, p, n) = max(0, |e(a) - e(p)|^2 - |e(a) - e(n)|^2 + margin)
//
// over triplets of an anchor word a, a positive p and a negative n (e on the unit sphere):
//  * positives of a: its z = 4 temporally closest words in its clip that do not overlap it (the
//    words ceil(W / S) = 4 and 5 before and after it at the defaults), and its k = 5 nearest words
//    under the DTW (dtw_neighbours.h), any clip; the positive of a triplet is one of these, drawn
//    uniformly, in one of its versions (the word itself or one of its time-warped copies), drawn
//    uniformly: the paper's augmentation;
//  * negatives of a: words of its clip at least `far_words` away, or words of another clip, one
//    of the two kinds drawn with probability 1/2 (the other clip's word uniformly among the
//    training words);
//  * mining (mine_semi_hard): within a batch, each anchor takes the semi-hard negative (FaceNet:
//    farther than its positive but within the margin) nearest to it among the batch's drawn
//    negatives that are valid negatives of it, or its own drawn negative when there is none.
// Training words are the pool's words outside held-out clips; anchors, positives and negatives
// are all training words. The input standardisation (mean and std per channel) comes from the
// training words.
//
// Optimiser: Adam (Kingma & Ba 2015; beta1 0.9, beta2 0.999, eps 1e-8), mean loss over a batch.
// Each epoch visits every training anchor once, in a seeded order, in batches of
// `batch_triplets`.
//
// Determinism: every random draw comes from SplitMix64 seeded by (seed, epoch) and drawn
// serially; a batch's rows are cut into fixed chunks of 32 whose gradients are summed in chunk
// order; so the weights are identical for any thread count. After each epoch the whole state
// (weights, Adam's moments, the losses) is handed to a checkpoint callback, and training resumes
// from such a state bit for bit.
// Thread-safety: one Train at a time per trainer; const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "common/status.h"
#include "engine/embedding/dtw_neighbours.h"
#include "engine/embedding/embedding_net.h"
#include "engine/embedding/word_pool.h"
#include "engine/signature/k_means.h"

namespace motif {

class SplitMix64;

struct EmbeddingTrainOptions {
  EmbeddingNetShape shape;  // frames and input_channels are set from the pool
  uint32_t epochs = 30;
  uint32_t batch_triplets = 128;
  double learning_rate = 1e-3;
  double margin = 0.2;
  uint32_t temporal_positives = 4;  // z
  uint32_t dtw_positives = 5;       // k (at most the neighbours found per word)
  uint32_t far_words = 30;          // same-clip negatives at least this many words away
  bool mine_semi_hard = true;
  uint64_t seed = 1;
  int threads = 0;
  // (batches done, batches in all epochs) during Train.
  std::function<void(uint64_t, uint64_t)> progress;
};

// InvalidArgument naming the option.
Status ValidateEmbeddingTrainOptions(const EmbeddingTrainOptions& options);

// Everything training needs to go on after an epoch: a checkpoint.
struct TrainingState {
  uint32_t epochs_done = 0;
  uint64_t adam_steps = 0;
  std::vector<float> parameters;
  std::vector<float> adam_m;
  std::vector<float> adam_v;
  std::vector<double> epoch_loss;    // mean triplet loss of each epoch
  std::vector<double> epoch_active;  // fraction of each epoch's triplets with a positive loss
};

// Fractions of triplets (d(a, p) < d(a, n)) ranked correctly by three distances.
struct TripletAccuracy {
  uint64_t triplets = 0;
  double raw = 0;        // L2 between the standardised network inputs
  double untrained = 0;  // the network at its initial weights
  double trained = 0;
};

class EmbeddingTrainer {
 public:
  // `neighbours`: FindDtwNeighbours(pool) (one list per pool word). InvalidArgument: bad
  // options, a pool with no training word, neighbours of another size.
  static Result<EmbeddingTrainer> Create(const WordPool& pool,
                                         std::vector<std::vector<WordNeighbour>> neighbours,
                                         const EmbeddingTrainOptions& options);

  const EmbeddingTrainOptions& options() const { return options_; }
  const EmbeddingNetShape& shape() const { return options_.shape; }
  uint64_t training_words() const { return train_words_.size(); }

  // The untrained network: initial weights from the seed, standardisation from the training words.
  const EmbeddingNet& initial_net() const { return initial_; }
  // A fresh state at epoch 0 (the initial weights, Adam's moments at zero).
  TrainingState InitialState() const;
  // The network of a state (its parameters with the standardisation).
  EmbeddingNet NetOf(const TrainingState& state) const;

  // Trains from `state` (epochs_done .. epochs), calling `checkpoint` after each epoch (a non-OK
  // status from it stops training and is returned). InvalidArgument: a state of another shape.
  Status Train(TrainingState* state,
               const std::function<Status(const TrainingState&)>& checkpoint = nullptr) const;

  // Held-out triplets: for each word of a held-out clip, each of its positives with one negative
  // (seeded), ranked by the three distances. triplets = 0 when nothing is held out.
  TripletAccuracy HeldOutAccuracy(const EmbeddingNet& trained) const;
  // Embeds version 0 of every pool word (n x D), in fixed chunks.
  RowMatrixXf EmbedPool(const EmbeddingNet& net) const;

 private:
  EmbeddingTrainer(const WordPool& pool, const EmbeddingTrainOptions& options)
      : pool_(&pool), options_(options) {}

  // The positives of `word`: temporal then DTW, each once; training words only if `train`.
  std::vector<uint32_t> Positives(uint64_t word, bool train) const;
  bool ValidNegative(uint64_t anchor, uint64_t other) const;
  // A negative of `anchor` drawn from `random`; training words only if `train`.
  uint32_t DrawNegative(uint64_t anchor, bool train, SplitMix64* random) const;

  // The steps of Train, one batch at a time (embedding_trainer.cc).
  struct BatchRow {
    uint32_t word;
    uint32_t version;
  };
  struct BatchWork;  // the batch's rows and buffers, and the arena its chunks run in
  // The training words with at least one positive.
  std::vector<uint32_t> TrainingAnchors() const;
  // Anchors order[first, first + count), a positive (a random version) and a negative each.
  void DrawBatchRows(const std::vector<uint32_t>& order, size_t first, size_t count,
                     SplitMix64* random, BatchWork* work) const;
  // The rows' inputs and embeddings, a fixed chunk of rows per task.
  void EmbedBatch(const EmbeddingNet& net, BatchWork* work) const;
  // The mean triplet loss of the batch's `count` triplets (added to *loss_sum and *active) and
  // its gradient per embedding row.
  void TripletLossGradient(size_t count, BatchWork* work, double* loss_sum, uint64_t* active) const;
  // The parameters' gradient: per chunk, then summed in chunk order (the same for any thread
  // count).
  void BatchGradient(const EmbeddingNet& net, BatchWork* work) const;
  // One Adam step of `net`'s parameters and the state's moments.
  void AdamStep(const std::vector<float>& gradient, TrainingState* state, EmbeddingNet* net) const;

  const WordPool* pool_;
  EmbeddingTrainOptions options_;
  std::vector<std::vector<WordNeighbour>> neighbours_;
  std::vector<uint32_t> train_words_;
  std::vector<std::vector<uint32_t>> positives_;  // per pool word, for training anchors
  EmbeddingNet initial_;
};

}  // namespace motif
