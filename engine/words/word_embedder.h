// WordEmbedder: a trained embedding (embedding_file.h) applied to the words of an archive or of
// a query clip: each word's network input (word_input.h) from its features and resampled rows,
// then the network, in fixed chunks of 32 words run in parallel (so the result does not depend
// on the thread count), and the nearest motif of each embedded word (NearestCentroid, the rule
// k-means built the motifs with).
// Thread-safety: const methods may be called from one thread at a time (they use the arena).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <tbb/task_arena.h>

#include "common/status.h"
#include "engine/embedding/embedding_file.h"
#include "engine/signature/k_means.h"
#include "engine/signature/word_batch.h"
#include "formats/motion/pose_frames.h"

namespace motif {

class WordEmbedder {
 public:
  // `joint_weights`: the archive's (one per joint). InvalidArgument if they do not select the
  // weighted joints the model was trained with, or the word geometry is the model's but the
  // layout has fewer joints.
  static Result<WordEmbedder> Create(const EmbeddingModel& model, const FrameLayout& layout,
                                     const std::vector<float>& joint_weights, int threads);

  const EmbeddingModel& model() const { return *model_; }
  uint32_t dims() const { return model_->net.shape().embedding_dims; }

  // The embeddings of every word of `batch` (which must have rows: WordStreamOptions::keep_rows
  // or ClipWords::AllWords(batch, true)) into rows [first_row, first_row + batch.size()) of `out`
  // (out must have that many rows and dims() columns).
  void Embed(const WordBatch& batch, RowMatrixXf* out, Eigen::Index first_row = 0) const;

 private:
  const EmbeddingModel* model_ = nullptr;
  FrameLayout layout_;
  uint32_t weighted_joints_ = 0;
  std::shared_ptr<tbb::task_arena> arena_;
};

// The nearest motif of each row of `embeddings`, in parallel (fixed chunks).
std::vector<uint16_t> NearestMotifs(const RowMatrixXf& embeddings, const RowMatrixXf& centroids,
                                    int threads);

}  // namespace motif
