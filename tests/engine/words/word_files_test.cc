// The files of `motifmine words` through the tensor file: the embedding, a checkpoint, the motifs
// and the signatures read back equal to what was written, and every kind's own checks refusing
// tensors that are missing, of the wrong shape or inconsistent (Corruption naming the tensor).
#include <gtest/gtest.h>

#include "common/split_mix64.h"
#include "engine/embedding/embedding_file.h"
#include "engine/words/word_files.h"

namespace motif {
namespace {

EmbeddingModel ExampleModel() {
  EmbeddingNetShape shape;
  shape.frames = 8;
  shape.input_channels = 6 * 2 + 4;
  shape.conv1_channels = 5;
  shape.conv2_channels = 4;
  shape.embedding_dims = 3;
  EmbeddingModel model;
  model.net = EmbeddingNet(shape);
  model.net.Initialize(9);
  std::vector<float> mean(shape.input_channels), deviation(shape.input_channels);
  for (uint32_t c = 0; c < shape.input_channels; ++c) {
    mean[c] = 0.5f * c;
    deviation[c] = 1.0f + c;
  }
  model.net.SetInputStandardisation(mean, deviation);
  model.words.word_frames = 8;
  model.words.stride_frames = 2;
  model.words.word_fps = 30;
  model.joints = {0, 3};
  model.joint_weights = {1.0f, 0.5f};
  model.archive_identity = 0x1234;
  model.training_key = 0x5678;
  model.seed = 7;
  model.pool_words = 321;
  model.epoch_loss = {0.3, 0.2};
  model.epoch_active = {0.9, 0.7};
  model.accuracy = {100, 0.8, 0.7, 0.9};
  return model;
}

// The file re-encoded with tensor `name` replaced by `tensor` (or dropped if its name is empty).
Result<TensorFile> Replaced(const TensorFile& file, const std::string& name, Tensor tensor) {
  TensorFile changed(file.kind());
  for (const Tensor& original : file.tensors()) {
    if (original.name != name) {
      changed.Add(original);
    } else if (!tensor.name.empty()) {
      changed.Add(tensor);
    }
  }
  MOTIF_ASSIGN_OR_RETURN(std::string bytes, EncodeTensorFile(changed));
  return DecodeTensorFile(bytes, "changed");
}

Tensor U32Tensor(const std::string& name, std::vector<uint32_t> values) {
  TensorFile file("x");
  file.AddU32(name, values);
  return file.tensors()[0];
}

TEST(EmbeddingFile, RoundTripsTheModelAndACheckpoint) {
  const EmbeddingModel model = ExampleModel();
  auto bytes = EncodeTensorFile(EmbeddingToTensorFile(model));
  ASSERT_TRUE(bytes.ok());
  auto file = DecodeTensorFile(*bytes, "m.mwe", kEmbeddingKind);
  ASSERT_TRUE(file.ok()) << file.status().ToString();
  auto read = EmbeddingFromTensorFile(*file);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->net.shape(), model.net.shape());
  EXPECT_EQ(read->net.parameters(), model.net.parameters());
  EXPECT_EQ(read->net.input_mean(), model.net.input_mean());
  EXPECT_EQ(read->net.input_std(), model.net.input_std());
  EXPECT_EQ(read->words.word_frames, 8u);
  EXPECT_EQ(read->words.stride_frames, 2u);
  EXPECT_EQ(read->words.word_fps, 30.0);
  EXPECT_EQ(read->joints, model.joints);
  EXPECT_EQ(read->joint_weights, model.joint_weights);
  EXPECT_EQ(read->training_key, 0x5678u);
  EXPECT_EQ(read->pool_words, 321u);
  EXPECT_EQ(read->epoch_loss, model.epoch_loss);
  EXPECT_EQ(read->accuracy.trained, 0.9);

  TrainingState state;
  state.epochs_done = 2;
  state.adam_steps = 17;
  state.parameters = model.net.parameters();
  state.parameters[3] += 1.0f;
  state.adam_m.assign(state.parameters.size(), 0.25f);
  state.adam_v.assign(state.parameters.size(), 0.5f);
  state.epoch_loss = {0.4, 0.35};
  state.epoch_active = {1.0, 0.8};
  auto checkpoint_bytes = EncodeTensorFile(CheckpointToTensorFile(model, state));
  ASSERT_TRUE(checkpoint_bytes.ok());
  auto checkpoint_file = DecodeTensorFile(*checkpoint_bytes, "m.mwe.checkpoint");
  ASSERT_TRUE(checkpoint_file.ok());
  EmbeddingModel described;
  auto resumed = CheckpointFromTensorFile(*checkpoint_file, &described);
  ASSERT_TRUE(resumed.ok()) << resumed.status().ToString();
  EXPECT_EQ(resumed->parameters, state.parameters);
  EXPECT_EQ(resumed->adam_m, state.adam_m);
  EXPECT_EQ(resumed->adam_v, state.adam_v);
  EXPECT_EQ(resumed->adam_steps, 17u);
  EXPECT_EQ(resumed->epochs_done, 2u);
  EXPECT_EQ(resumed->epoch_loss, state.epoch_loss);
  // Each kind refuses the other.
  EXPECT_TRUE(EmbeddingFromTensorFile(*checkpoint_file).status().IsInvalidArgument());
  EXPECT_TRUE(CheckpointFromTensorFile(*file, &described).status().IsInvalidArgument());
}

TEST(EmbeddingFile, RefusesMissingOrInconsistentTensors) {
  const TensorFile file = EmbeddingToTensorFile(ExampleModel());
  auto expect_corrupt = [&](const std::string& name, Tensor tensor, const std::string& text) {
    auto changed = Replaced(file, name, tensor);
    ASSERT_TRUE(changed.ok());
    auto model = EmbeddingFromTensorFile(*changed);
    ASSERT_FALSE(model.ok()) << name;
    EXPECT_TRUE(model.status().IsCorruption()) << model.status().ToString();
    EXPECT_NE(model.status().message().find(text), std::string::npos) << model.status().ToString();
  };
  expect_corrupt("conv2.weight", Tensor{}, "'conv2.weight' is missing");
  // A shape whose conv1 has 6 channels: the stored conv1 block no longer fits.
  expect_corrupt("net.shape", U32Tensor("net.shape", {8, 16, 6, 3, 4, 3, 2, 3}), "conv1.weight");
  // A kernel longer than the word.
  expect_corrupt("net.shape", U32Tensor("net.shape", {8, 16, 5, 9, 4, 3, 2, 3}), "net.shape");
  // Three joints for 16 input channels.
  expect_corrupt("joints", U32Tensor("joints", {0, 1, 2}), "joint.weights");
  expect_corrupt("word.geometry", U32Tensor("word.geometry", {9, 2}), "word geometry");
}

SignatureSet ExampleSignatures() {
  SignatureSet set;
  set.motifs_identity = 11;
  set.archive_identity = 12;
  set.motif_count = 3;
  set.clip_words = {2, 0, 3};
  set.word_motifs = {0, 2, 2, 2, 1};
  set.document_frequencies = {1, 1, 2};
  set.take_count = 2;
  set.signatures = {1, 0, 1, 0, 0, 0, 0, 0.5, 2};
  return set;
}

TEST(WordFiles, MotifsAndSignaturesRoundTrip) {
  MotifSet motifs;
  motifs.centroids = RowMatrixXf(2, 3);
  motifs.centroids << 1, 2, 3, -1, -2, -3;
  motifs.cluster_sizes = {4, 5};
  motifs.inertia = 2.5;
  motifs.iterations = 7;
  motifs.embedding_identity = 21;
  motifs.archive_identity = 22;
  motifs.seed = 23;
  auto bytes = EncodeTensorFile(MotifsToTensorFile(motifs));
  ASSERT_TRUE(bytes.ok());
  auto read = MotifsFromTensorFile(*DecodeTensorFile(*bytes, "m.mwm"));
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->centroids, motifs.centroids);
  EXPECT_EQ(read->cluster_sizes, motifs.cluster_sizes);
  EXPECT_EQ(read->inertia, 2.5);
  EXPECT_EQ(read->iterations, 7u);
  EXPECT_EQ(read->embedding_identity, 21u);

  const SignatureSet set = ExampleSignatures();
  auto signature_bytes = EncodeTensorFile(SignaturesToTensorFile(set));
  ASSERT_TRUE(signature_bytes.ok());
  auto signatures = SignaturesFromTensorFile(*DecodeTensorFile(*signature_bytes, "s.mws"));
  ASSERT_TRUE(signatures.ok()) << signatures.status().ToString();
  EXPECT_EQ(signatures->word_motifs, set.word_motifs);
  EXPECT_EQ(signatures->signatures, set.signatures);
  EXPECT_EQ(signatures->ClipFirstWords(), (std::vector<uint64_t>{0, 2, 2}));
  EXPECT_EQ(signatures->words.word_frames, 16u);
  EXPECT_TRUE(SignaturesFromTensorFile(MotifsToTensorFile(motifs)).status().IsInvalidArgument());
}

TEST(WordFiles, SignaturesThatDoNotAddUpAreRefused) {
  auto check = [](SignatureSet set, const std::string& text) {
    auto read = SignaturesFromTensorFile(SignaturesToTensorFile(set));
    ASSERT_FALSE(read.ok()) << text;
    EXPECT_TRUE(read.status().IsCorruption());
    EXPECT_NE(read.status().message().find(text), std::string::npos) << read.status().ToString();
  };
  SignatureSet set = ExampleSignatures();
  set.word_motifs[4] = 3;
  check(set, "word 4 has motif 3");
  set = ExampleSignatures();
  set.clip_words = {2, 0, 2};
  set.signatures.resize(9);
  check(set, "4 words in the clips");
  set = ExampleSignatures();
  set.take_count = 3;
  check(set, "take count 3");
  set = ExampleSignatures();
  set.document_frequencies[0] = 5;
  check(set, "document frequency 5");
}

}  // namespace
}  // namespace motif
