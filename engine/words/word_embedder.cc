#include "engine/words/word_embedder.h"

#include <algorithm>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "engine/embedding/word_input.h"
#include "engine/signature/frame_resampler.h"

namespace motif {
namespace {

constexpr size_t kChunkWords = 32;

}  // namespace

Result<WordEmbedder> WordEmbedder::Create(const EmbeddingModel& model, const FrameLayout& layout,
                                          const std::vector<float>& joint_weights, int threads) {
  MOTIF_ASSIGN_OR_RETURN(FrameResampler resampler, FrameResampler::Create(layout, joint_weights));
  if (resampler.joints() != model.joints) {
    return Status::InvalidArgument(
        "the embedding was trained on " + std::to_string(model.joints.size()) +
        " weighted joints that are not the archive's " + std::to_string(resampler.joints().size()) +
        " (another skeleton or another weights file; train an embedding for this archive)");
  }
  WordEmbedder embedder;
  embedder.model_ = &model;
  embedder.layout_ = layout;
  embedder.weighted_joints_ = resampler.weighted_joint_count();
  // A copy of the constant: make_shared takes its arguments by reference, and TBB does not
  // define task_arena::automatic out of line.
  const int concurrency = threads > 0 ? threads : int{tbb::task_arena::automatic};
  embedder.arena_ = std::make_shared<tbb::task_arena>(concurrency);
  return embedder;
}

void WordEmbedder::Embed(const WordBatch& batch, RowMatrixXf* out, Eigen::Index first_row) const {
  MOTIF_CHECK(batch.has_rows() || batch.empty());
  const EmbeddingNet& net = model_->net;
  const uint32_t frames = batch.word_frames();
  MOTIF_CHECK(batch.empty() || frames == net.shape().frames);
  const double word_fps = model_->words.word_fps;
  const size_t input_size = net.shape().input_size();
  const size_t chunks = (batch.size() + kChunkWords - 1) / kChunkWords;
  arena_->execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& range) {
          EmbeddingNet::Workspace workspace;
          std::vector<float> root(static_cast<size_t>(frames) * kRootMotionChannels);
          for (size_t chunk = range.begin(); chunk != range.end(); ++chunk) {
            const size_t begin = chunk * kChunkWords;
            const size_t end = std::min(batch.size(), begin + kChunkWords);
            EmbeddingNet::Matrix input(static_cast<Eigen::Index>(end - begin),
                                       static_cast<Eigen::Index>(input_size));
            for (size_t word = begin; word < end; ++word) {
              RootMotionFromRows(layout_, batch.rows(word), frames, word_fps, 1.0, root.data());
              EncodeWordInput(batch.word(word), root.data(), frames, weighted_joints_,
                              input.row(static_cast<Eigen::Index>(word - begin)).data());
            }
            net.Forward(input, &workspace);
            out->middleRows(first_row + static_cast<Eigen::Index>(begin),
                            static_cast<Eigen::Index>(end - begin)) = workspace.embeddings;
          }
        });
  });
}

std::vector<uint16_t> NearestMotifs(const RowMatrixXf& embeddings, const RowMatrixXf& centroids,
                                    int threads) {
  std::vector<uint16_t> motifs(static_cast<size_t>(embeddings.rows()));
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, motifs.size(), 1024),
                      [&](const tbb::blocked_range<size_t>& range) {
                        for (size_t word = range.begin(); word != range.end(); ++word) {
                          motifs[word] = static_cast<uint16_t>(NearestCentroid(
                              centroids, embeddings.row(static_cast<Eigen::Index>(word)).data()));
                        }
                      });
  });
  return motifs;
}

}  // namespace motif
