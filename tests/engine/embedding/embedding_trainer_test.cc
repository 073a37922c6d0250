#include "engine/embedding/embedding_trainer.h"

#include <gtest/gtest.h>

#include "tests/engine/embedding/embedding_test_util.h"

namespace motif::testing {
namespace {

struct Fixture {
  std::vector<ClipWords> clips;
  WordPool pool;
  std::vector<std::vector<WordNeighbour>> neighbours;
};

Fixture MakeFixture(uint64_t frames, uint64_t seed) {
  Fixture fixture{ClipWordsOf(MakeSynthClips(frames, seed)), WordPool(), {}};
  WordPoolOptions options;
  options.held_out_fraction = 0.2;
  fixture.pool = PoolOf(fixture.clips, options);
  auto neighbours = FindDtwNeighbours(fixture.pool, DtwNeighbourOptions{});
  EXPECT_TRUE(neighbours.ok());
  fixture.neighbours = std::move(*neighbours);
  return fixture;
}

EmbeddingTrainOptions SmallOptions() {
  EmbeddingTrainOptions options;
  options.shape.conv1_channels = 32;
  options.shape.conv2_channels = 32;
  options.shape.embedding_dims = 16;
  options.batch_triplets = 64;
  options.epochs = 8;
  return options;
}

TEST(EmbeddingTrainer, TrainingLowersTheLossAndBeatsTheUntrainedNetOnHeldOutWords) {
  const Fixture fixture = MakeFixture(30000, 21);
  auto trainer = EmbeddingTrainer::Create(fixture.pool, fixture.neighbours, SmallOptions());
  ASSERT_TRUE(trainer.ok()) << trainer.status().ToString();
  TrainingState state = trainer->InitialState();
  ASSERT_TRUE(trainer->Train(&state).ok());
  ASSERT_EQ(state.epoch_loss.size(), 8u);
  std::printf("loss per epoch:");
  for (double loss : state.epoch_loss) std::printf(" %.4f", loss);
  std::printf("\n");
  EXPECT_LT(state.epoch_loss.back(), 0.7 * state.epoch_loss.front());
  const TripletAccuracy accuracy = trainer->HeldOutAccuracy(trainer->NetOf(state));
  std::printf("held-out triplets %llu: raw %.3f untrained %.3f trained %.3f\n",
              static_cast<unsigned long long>(accuracy.triplets), accuracy.raw, accuracy.untrained,
              accuracy.trained);
  EXPECT_GT(accuracy.triplets, 100u);
  EXPECT_GT(accuracy.trained, accuracy.untrained);
}

TEST(EmbeddingTrainer, WeightsAreIdenticalForAnyThreadCountAndWhenResumed) {
  const Fixture fixture = MakeFixture(8000, 4);
  EmbeddingTrainOptions options = SmallOptions();
  options.epochs = 3;
  options.threads = 1;
  auto serial = EmbeddingTrainer::Create(fixture.pool, fixture.neighbours, options);
  options.threads = 2;
  auto parallel = EmbeddingTrainer::Create(fixture.pool, fixture.neighbours, options);
  ASSERT_TRUE(serial.ok() && parallel.ok());
  TrainingState one = serial->InitialState();
  TrainingState two = parallel->InitialState();
  ASSERT_TRUE(serial->Train(&one).ok());
  // Interrupted after the first epoch (the checkpoint's copy), then resumed.
  TrainingState checkpoint;
  ASSERT_TRUE(parallel
                  ->Train(&two,
                          [&](const TrainingState& state) {
                            if (state.epochs_done == 1) {
                              checkpoint = state;
                              return Status::IOError("stop here");
                            }
                            return Status::Ok();
                          })
                  .IsIOError());
  ASSERT_EQ(checkpoint.epochs_done, 1u);
  ASSERT_TRUE(parallel->Train(&checkpoint).ok());
  EXPECT_EQ(checkpoint.parameters, one.parameters);
  EXPECT_EQ(checkpoint.adam_m, one.adam_m);
  EXPECT_EQ(checkpoint.epoch_loss, one.epoch_loss);
  EXPECT_NE(one.parameters, serial->InitialState().parameters);
}

TEST(EmbeddingTrainer, RefusesBadOptions) {
  const Fixture fixture = MakeFixture(3000, 2);
  EmbeddingTrainOptions options = SmallOptions();
  options.margin = 0;
  EXPECT_TRUE(EmbeddingTrainer::Create(fixture.pool, fixture.neighbours, options)
                  .status()
                  .IsInvalidArgument());
  options = SmallOptions();
  EXPECT_TRUE(EmbeddingTrainer::Create(fixture.pool, {}, options).status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif::testing
