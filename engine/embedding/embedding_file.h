// The trained word embedding as a tensor file of kind "embedding" (.mwe), and training
// checkpoints as tensor files of kind "checkpoint" (docs/formats/tensor_file.md, section 8,
// lists every tensor): the network's shape, standardisation and parameters, the word geometry
// and the weighted joints it was trained for, what it was trained on (the archive's identity
// and a key of every option that changes the weights), the loss per epoch and the held-out
// triplet accuracy. A checkpoint adds Adam's state, so training resumes bit for bit.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "engine/embedding/embedding_net.h"
#include "engine/embedding/embedding_trainer.h"
#include "engine/signature/word_grid.h"
#include "formats/tensor_file/tensor_file.h"

namespace motif {

inline constexpr char kEmbeddingKind[] = "embedding";
inline constexpr char kCheckpointKind[] = "checkpoint";

struct EmbeddingModel {
  EmbeddingNet net;
  WordOptions words;
  std::vector<uint32_t> joints;      // archive index of each weighted joint, ascending
  std::vector<float> joint_weights;  // their weights
  uint64_t archive_identity = 0;     // the archive trained on
  uint64_t training_key = 0;         // TrainingKey of the options it was trained with
  uint64_t seed = 0;
  uint64_t pool_words = 0;  // words trained on (and held out)
  std::vector<double> epoch_loss;
  std::vector<double> epoch_active;
  TripletAccuracy accuracy;  // held out (triplets 0: none)
};

// The tensors of an embedding file, and the model from them. Corruption naming the tensor when
// one is missing, of the wrong type or shape, or the shape is not a valid network.
TensorFile EmbeddingToTensorFile(const EmbeddingModel& model);
Result<EmbeddingModel> EmbeddingFromTensorFile(const TensorFile& file);

// A checkpoint: the model's description (its net's parameters are the state's) and the state.
TensorFile CheckpointToTensorFile(const EmbeddingModel& model, const TrainingState& state);
// The state and the model of a checkpoint. Same errors.
Result<TrainingState> CheckpointFromTensorFile(const TensorFile& file, EmbeddingModel* model);

}  // namespace motif
