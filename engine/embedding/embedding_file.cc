#include "engine/embedding/embedding_file.h"

#include <string>

namespace motif {
namespace {

void AddModel(const EmbeddingModel& model, TensorFile* file) {
  const EmbeddingNetShape& s = model.net.shape();
  const uint32_t shape[8] = {s.frames,       s.input_channels, s.conv1_channels,
                             s.conv1_kernel, s.conv2_channels, s.conv2_kernel,
                             s.conv2_stride, s.embedding_dims};
  file->AddU32("net.shape", shape);
  const uint32_t geometry[2] = {model.words.word_frames, model.words.stride_frames};
  file->AddU32("word.geometry", geometry);
  const double fps[1] = {model.words.word_fps};
  file->AddF64("word.fps", fps);
  file->AddU32("joints", model.joints);
  file->AddF32("joint.weights", model.joint_weights);
  file->AddF32("input.mean", model.net.input_mean());
  file->AddF32("input.std", model.net.input_std());
  const std::vector<float>& p = model.net.parameters();
  auto block = [&](const char* name, size_t begin, size_t end, uint64_t rows, uint64_t cols) {
    std::span<const float> values(p.data() + begin, end - begin);
    if (cols == 1) {
      file->AddF32(name, values);
    } else {
      file->AddF32Matrix(name, rows, cols, values);
    }
  };
  block("conv1.weight", s.conv1_weight_offset(), s.conv1_bias_offset(),
        uint64_t{s.conv1_kernel} * s.input_channels, s.conv1_channels);
  block("conv1.bias", s.conv1_bias_offset(), s.conv2_weight_offset(), s.conv1_channels, 1);
  block("conv2.weight", s.conv2_weight_offset(), s.conv2_bias_offset(),
        uint64_t{s.conv2_kernel} * s.conv1_channels, s.conv2_channels);
  block("conv2.bias", s.conv2_bias_offset(), s.linear_weight_offset(), s.conv2_channels, 1);
  block("linear.weight", s.linear_weight_offset(), s.linear_bias_offset(), s.flat_size(),
        s.embedding_dims);
  block("linear.bias", s.linear_bias_offset(), s.parameter_count(), s.embedding_dims, 1);
  const uint64_t identity[3] = {model.archive_identity, model.training_key, model.seed};
  file->AddU64("training.identity", identity);
  const uint64_t pool[1] = {model.pool_words};
  file->AddU64("training.words", pool);
  file->AddF64("training.loss", model.epoch_loss);
  file->AddF64("training.active", model.epoch_active);
  const double accuracy[4] = {static_cast<double>(model.accuracy.triplets), model.accuracy.raw,
                              model.accuracy.untrained, model.accuracy.trained};
  file->AddF64("training.accuracy", accuracy);
}

Result<EmbeddingModel> ReadModel(const TensorFile& file) {
  EmbeddingModel model;
  MOTIF_ASSIGN_OR_RETURN(std::vector<uint32_t> shape_values, file.U32("net.shape", 8));
  EmbeddingNetShape shape;
  shape.frames = shape_values[0];
  shape.input_channels = shape_values[1];
  shape.conv1_channels = shape_values[2];
  shape.conv1_kernel = shape_values[3];
  shape.conv2_channels = shape_values[4];
  shape.conv2_kernel = shape_values[5];
  shape.conv2_stride = shape_values[6];
  shape.embedding_dims = shape_values[7];
  if (Status status = ValidateEmbeddingNetShape(shape); !status.ok()) {
    return Status::Corruption(file.kind() + " file: tensor 'net.shape': " + status.message());
  }
  MOTIF_ASSIGN_OR_RETURN(std::vector<uint32_t> geometry, file.U32("word.geometry", 2));
  MOTIF_ASSIGN_OR_RETURN(double fps, file.ScalarF64("word.fps"));
  model.words.word_frames = geometry[0];
  model.words.stride_frames = geometry[1];
  model.words.word_fps = fps;
  if (!ValidateWordOptions(model.words).ok() || model.words.word_frames != shape.frames) {
    return Status::Corruption(file.kind() + " file: word geometry " + std::to_string(geometry[0]) +
                              " / " + std::to_string(geometry[1]) + " at " + std::to_string(fps) +
                              " Hz does not fit the network");
  }
  MOTIF_ASSIGN_OR_RETURN(model.joints, file.U32("joints"));
  MOTIF_ASSIGN_OR_RETURN(model.joint_weights, file.F32("joint.weights", model.joints.size()));
  if (model.joints.empty() || shape.input_channels != 6 * model.joints.size() + 4) {
    return Status::Corruption(file.kind() + " file: " + std::to_string(model.joints.size()) +
                              " weighted joints do not make the network's " +
                              std::to_string(shape.input_channels) + " input channels");
  }
  model.net = EmbeddingNet(shape);
  MOTIF_ASSIGN_OR_RETURN(std::vector<float> mean, file.F32("input.mean", shape.input_channels));
  MOTIF_ASSIGN_OR_RETURN(std::vector<float> deviation, file.F32("input.std", shape.input_channels));
  model.net.SetInputStandardisation(std::move(mean), std::move(deviation));
  std::vector<float>& p = model.net.mutable_parameters();
  auto block = [&](const char* name, size_t begin, size_t end, uint64_t rows,
                   uint64_t cols) -> Status {
    Result<std::vector<float>> values =
        cols == 1 ? file.F32(name, rows) : file.F32Matrix(name, rows, cols);
    if (!values.ok()) return values.status();
    std::copy(values->begin(), values->end(), p.begin() + static_cast<std::ptrdiff_t>(begin));
    (void)end;
    return Status::Ok();
  };
  const EmbeddingNetShape& s = shape;
  MOTIF_RETURN_IF_ERROR(block("conv1.weight", s.conv1_weight_offset(), s.conv1_bias_offset(),
                              uint64_t{s.conv1_kernel} * s.input_channels, s.conv1_channels));
  MOTIF_RETURN_IF_ERROR(block("conv1.bias", s.conv1_bias_offset(), 0, s.conv1_channels, 1));
  MOTIF_RETURN_IF_ERROR(block("conv2.weight", s.conv2_weight_offset(), 0,
                              uint64_t{s.conv2_kernel} * s.conv1_channels, s.conv2_channels));
  MOTIF_RETURN_IF_ERROR(block("conv2.bias", s.conv2_bias_offset(), 0, s.conv2_channels, 1));
  MOTIF_RETURN_IF_ERROR(
      block("linear.weight", s.linear_weight_offset(), 0, s.flat_size(), s.embedding_dims));
  MOTIF_RETURN_IF_ERROR(block("linear.bias", s.linear_bias_offset(), 0, s.embedding_dims, 1));
  MOTIF_ASSIGN_OR_RETURN(std::vector<uint64_t> identity, file.U64("training.identity", 3));
  model.archive_identity = identity[0];
  model.training_key = identity[1];
  model.seed = identity[2];
  MOTIF_ASSIGN_OR_RETURN(model.pool_words, file.ScalarU64("training.words"));
  MOTIF_ASSIGN_OR_RETURN(model.epoch_loss, file.F64("training.loss"));
  MOTIF_ASSIGN_OR_RETURN(model.epoch_active, file.F64("training.active", model.epoch_loss.size()));
  MOTIF_ASSIGN_OR_RETURN(std::vector<double> accuracy, file.F64("training.accuracy", 4));
  model.accuracy.triplets = static_cast<uint64_t>(accuracy[0]);
  model.accuracy.raw = accuracy[1];
  model.accuracy.untrained = accuracy[2];
  model.accuracy.trained = accuracy[3];
  return model;
}

}  // namespace

TensorFile EmbeddingToTensorFile(const EmbeddingModel& model) {
  TensorFile file(kEmbeddingKind);
  AddModel(model, &file);
  return file;
}

Result<EmbeddingModel> EmbeddingFromTensorFile(const TensorFile& file) {
  if (file.kind() != kEmbeddingKind) {
    return Status::InvalidArgument("a tensor file of kind '" + file.kind() + "', not '" +
                                   kEmbeddingKind + "'");
  }
  return ReadModel(file);
}

TensorFile CheckpointToTensorFile(const EmbeddingModel& model, const TrainingState& state) {
  EmbeddingModel copy = model;
  copy.net.mutable_parameters() = state.parameters;
  copy.epoch_loss = state.epoch_loss;
  copy.epoch_active = state.epoch_active;
  TensorFile file(kCheckpointKind);
  AddModel(copy, &file);
  file.AddF32("adam.m", state.adam_m);
  file.AddF32("adam.v", state.adam_v);
  const uint64_t progress[2] = {state.epochs_done, state.adam_steps};
  file.AddU64("adam.progress", progress);
  return file;
}

Result<TrainingState> CheckpointFromTensorFile(const TensorFile& file, EmbeddingModel* model) {
  if (file.kind() != kCheckpointKind) {
    return Status::InvalidArgument("a tensor file of kind '" + file.kind() + "', not '" +
                                   kCheckpointKind + "'");
  }
  MOTIF_ASSIGN_OR_RETURN(*model, ReadModel(file));
  TrainingState state;
  const size_t count = model->net.parameters().size();
  state.parameters = model->net.parameters();
  MOTIF_ASSIGN_OR_RETURN(state.adam_m, file.F32("adam.m", count));
  MOTIF_ASSIGN_OR_RETURN(state.adam_v, file.F32("adam.v", count));
  MOTIF_ASSIGN_OR_RETURN(std::vector<uint64_t> progress, file.U64("adam.progress", 2));
  state.epochs_done = static_cast<uint32_t>(progress[0]);
  state.adam_steps = progress[1];
  state.epoch_loss = model->epoch_loss;
  state.epoch_active = model->epoch_active;
  if (state.epoch_loss.size() != state.epochs_done) {
    return Status::Corruption(file.kind() + " file: " + std::to_string(state.epoch_loss.size()) +
                              " epoch losses for " + std::to_string(state.epochs_done) +
                              " epochs done");
  }
  return state;
}

}  // namespace motif
