// The movement distance between whole takes (take_movement.h): its arithmetic on hand-made
// summaries, its blindness to tempo, and on real studio takes, the same action found in another
// style before another action.
#include "engine/signature/take_movement.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "engine/ingest/archive_import.h"
#include "engine/signature/take_retrieval.h"
#include "tests/testing/mocap_data.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

// A take whose only varying value is its travel speed; its steps are `steps`.
TakeMovement Moving(double speed, const Eigen::MatrixXd& steps) {
  TakeMovement take;
  take.shares = {0.5, 0.5};
  take.windings = {1.0, 2.0};
  take.travel = {speed, 0.0, 0.0};
  take.steps = steps;
  return take;
}

Eigen::MatrixXd Ramp(int rows, int repeat) {
  Eigen::MatrixXd steps(rows * repeat, 2);
  for (int row = 0; row < rows * repeat; ++row) steps.row(row) << row / repeat, 1.0;
  return steps;
}

// Speeds 0, 1, 2 z-score to -1.22, 0, 1.22; the pairs 1, 1, 2 apart (times one scale) have the
// median 1, so the summary term is exactly |a - b|; equal steps add nothing.
TEST(TakeMovement, SummaryTermIsTheZScoredDistanceOverItsMedian) {
  const Eigen::MatrixXd steps = Ramp(4, 1);
  const Eigen::MatrixXd d =
      MovementDistanceMatrix({Moving(0, steps), Moving(1, steps), Moving(2, steps)}, 1);
  EXPECT_NEAR(d(0, 1), 1.0, 1e-12);
  EXPECT_NEAR(d(1, 2), 1.0, 1e-12);
  EXPECT_NEAR(d(0, 2), 2.0, 1e-12);
  EXPECT_EQ(d(2, 0), d(0, 2));
  EXPECT_EQ(d(1, 1), 0.0);
}

// The same steps at half the tempo (every row twice) warp onto each other at no cost; a reversed
// sequence does not.
TEST(TakeMovement, StepsWarpAwayTheTempo) {
  const Eigen::MatrixXd slow = Ramp(5, 2);
  const Eigen::MatrixXd reversed = Ramp(5, 1).colwise().reverse();
  const Eigen::MatrixXd d = MovementDistanceMatrix(
      {Moving(1, Ramp(5, 1)), Moving(1, slow), Moving(1, reversed)}, 2);
  EXPECT_EQ(d(0, 1), 0.0);
  EXPECT_GT(d(0, 2), 0.5);
  EXPECT_GT(d(1, 2), 0.5);
}

TEST(TakeMovement, TheThreadCountDoesNotChangeAnyBit) {
  std::vector<TakeMovement> takes;
  for (int idx = 0; idx < 9; ++idx) {
    takes.push_back(Moving(idx * idx % 5, Ramp(3 + idx, 1 + idx % 2)));
  }
  EXPECT_EQ(MovementDistanceMatrix(takes, 1), MovementDistanceMatrix(takes, 2));
}

// The studio archive's 140 takes (10 actions, 7 styles, 2 takes each): every take's nearest take
// is of its action, and of its 5 nearest at least 0.9 are (docs/benchmarks.md, "Whole-take
// retrieval across styles", measures 1.000 and 0.923; the pose DTW gives 0.456 at 5).
TEST(TakeMovement, StudioTakesFindTheirActionAcrossStyles) {
  MOTIF_REQUIRE_STUDIO_RIG_DATA();
  testing::TempDir dir;
  const std::string archive = dir.File("styles.mfs");
  auto imported = ImportIntoArchive(archive, {testing::StudioRigDir() + "/bvh"}, {});
  ASSERT_TRUE(imported.ok()) << imported.status().ToString();
  auto reader = FrameFileReader::Open(archive);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  std::vector<uint32_t> clips;
  std::vector<std::string> actions;  // dataset-2_{ACTION}_{STYLE}_{ID}
  for (uint32_t clip = 0; clip < (*reader)->clips().size(); ++clip) {
    const std::string& name = (*reader)->clips()[clip].name;
    clips.push_back(clip);
    actions.push_back(name.substr(0, name.rfind('_', name.rfind('_') - 1)));
  }
  ASSERT_EQ(clips.size(), 140u);
  auto distances = TakeMovementMatrix(**reader, clips, 2);
  ASSERT_TRUE(distances.ok()) << distances.status().ToString();
  std::vector<uint32_t> labels(actions.size());
  for (size_t take = 0; take < actions.size(); ++take) {
    labels[take] = static_cast<uint32_t>(
        std::find(actions.begin(), actions.end(), actions[take]) - actions.begin());
  }
  EXPECT_EQ(LeaveOneOutKnn(*distances, labels, static_cast<uint32_t>(actions.size()), 1).accuracy,
            1.0);
  EXPECT_GE(PrecisionAtK(*distances, labels, 5), 0.9);
}

}  // namespace
}  // namespace motif
