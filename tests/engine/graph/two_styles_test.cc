// The motion graph on an archive of two styles that share a held pose: style 0 swings every
// joint about X, style 1 about Z, and every clip holds the same neutral pose for 1.5 s between
// its swings (1.5 s each). The pose windows of the holds match across the styles, so transitions
// join them; the signature constraint, which compares the motion before and after, must cut those.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "engine/graph/motion_graph.h"
#include "engine/graph/transition_search.h"
#include "engine/graph/transition_signatures.h"
#include "engine/graph/walk_take.h"
#include "engine/trellis/trellis_builder.h"
#include "formats/export/bvh_writer.h"
#include "tests/engine/words/words_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

constexpr double kFps = 120;
constexpr uint32_t kJoints = 6;
constexpr uint64_t kSwingFrames = 240;  // 2 s
constexpr uint64_t kHoldFrames = 60;    // 0.5 s

// swing, hold, swing, hold, swing: 900 frames.
ClipFrames StyleClip(int style, int index, double phase) {
  const FrameLayout layout{kJoints};
  const uint64_t frames = 3 * kSwingFrames + 2 * kHoldFrames;
  ClipFrames clip = ChainClip("style" + std::to_string(style) + "_" + std::to_string(index), frames,
                              kJoints, kFps);
  for (uint64_t frame = 0; frame < frames; ++frame) {
    const uint64_t in_cycle = frame % (kSwingFrames + kHoldFrames);
    const bool hold = in_cycle >= kSwingFrames;
    const double t = static_cast<double>(frame) / kFps;
    float* row = &clip.rows[frame * layout.stride()];
    for (uint32_t joint = 0; joint < kJoints; ++joint) {
      // The swing fades in and out over its first and last 0.5 s, so a hold is reached smoothly.
      const double edge = std::min<double>(in_cycle, kSwingFrames - in_cycle) / 60.0;
      const double envelope = hold ? 0.0 : std::min(1.0, edge);
      const double angle = 0.7 * envelope * std::sin(2 * M_PI * 1.1 * t + phase + 0.5 * joint);
      const Eigen::Vector3d axis = style == 0 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
      // The hold sways a little about Y, the same in both styles, so that the nearest held poses
      // of a held pose are spread over every clip rather than tied at distance 0.
      const double sway = 0.05 * std::sin(2 * M_PI * 0.5 * t + phase + 0.5 * joint);
      StoreQuaternion(Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis) *
                                         Eigen::AngleAxisd(sway, Eigen::Vector3d::UnitY())),
                      layout, joint, row);
    }
    row[layout.height_offset()] = 1.0f;
  }
  return clip;
}

class TwoStylesTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    archive_ = dir_->File("styles.mfs");
    std::vector<ClipFrames> clips;
    for (int index = 0; index < 4; ++index) {
      for (int style = 0; style < 2; ++style) {
        clips.push_back(StyleClip(style, index, 0.9 * index + 0.4 * style));
      }
    }
    WriteClips(archive_, ChainSkeleton(kJoints), clips, kFps);
    WordsOptions words = SmallWordsOptions(12);
    words.train.epochs = 4;
    ASSERT_TRUE(BuildWords(archive_, DefaultWordsPaths(archive_), words).ok());
    TrellisOptions trellis;
    trellis.search = TrellisSearchMode::kExact;
    trellis.threads = 2;
    auto built = BuildTrellis(archive_, DefaultTrellisPath(archive_), trellis);
    ASSERT_TRUE(built.ok()) << built.status().ToString();
  }
  static void TearDownTestSuite() { delete dir_; }

  static int StyleOf(const FrameFileReader& reader, uint32_t clip) {
    return reader.clips()[clip].name[5] - '0';
  }
  // The transitions, measured against the signatures, and the graph with or without the
  // constraint.
  static MotionGraph Graph(const FrameFileReader& reader, bool constrained,
                           std::vector<GraphTransition>* measured = nullptr) {
    auto trellis = TrellisFileReader::Open(DefaultTrellisPath(archive_));
    EXPECT_TRUE(trellis.ok());
    const ClipBounds clips = ClipBoundsOf(reader);
    auto found = FindTransitions(**trellis, clips, TransitionOptions{});
    EXPECT_TRUE(found.ok()) << found.status().ToString();
    std::vector<GraphTransition> transitions;
    for (const Transition& t : found->transitions) transitions.push_back({t});
    auto words = LoadWords(reader, DefaultWordsPaths(archive_), false);
    EXPECT_TRUE(words.ok());
    auto constraint = MeasureTransitionSignatures(reader, *words, clips, &transitions, 2);
    EXPECT_TRUE(constraint.ok()) << constraint.status().ToString();
    if (constrained) PruneBySignature(constraint->threshold, &transitions);
    if (measured) *measured = transitions;
    return BuildMotionGraph(clips, std::move(transitions), 30);
  }

  static TempDir* dir_;
  static std::string archive_;
};
TempDir* TwoStylesTest::dir_ = nullptr;
std::string TwoStylesTest::archive_;

TEST_F(TwoStylesTest, TransitionsJoinBothStylesAndTheConstraintCutsTheCrossings) {
  auto reader = OpenArchive(archive_);
  const ClipBounds clips = ClipBoundsOf(*reader);
  std::vector<GraphTransition> measured;
  Graph(*reader, false, &measured);
  uint64_t crossing = 0;
  uint64_t crossing_kept = 0;
  uint64_t within = 0;
  uint64_t within_kept = 0;
  auto words = LoadWords(*reader, DefaultWordsPaths(archive_), false);
  std::vector<GraphTransition> pruned = measured;
  auto constraint = MeasureTransitionSignatures(*reader, *words, clips, &pruned, 2);
  ASSERT_TRUE(constraint.ok());
  PruneBySignature(constraint->threshold, &pruned);
  for (size_t idx = 0; idx < measured.size(); ++idx) {
    const Transition& t = measured[idx].transition;
    const bool cross =
        StyleOf(*reader, clips.ClipOf(t.source)) != StyleOf(*reader, clips.ClipOf(t.target));
    const bool kept = pruned[idx].fate == TransitionFate::kKept;
    (cross ? crossing : within) += 1;
    (cross ? crossing_kept : within_kept) += kept;
  }
  // Both kinds exist (the holds match across styles; the swings within a style).
  EXPECT_GT(crossing, 10u);
  EXPECT_GT(within, 10u);
  // The constraint keeps most transitions within a style and few that cross.
  EXPECT_LT(static_cast<double>(crossing_kept), 0.1 * static_cast<double>(crossing))
      << crossing_kept << " of " << crossing << " crossings kept";
  EXPECT_GT(static_cast<double>(within_kept), 0.5 * static_cast<double>(within))
      << within_kept << " of " << within << " kept within a style";
}

TEST_F(TwoStylesTest, AConstrainedWalkStaysInItsStyleAndAnUnconstrainedOneLeavesIt) {
  auto reader = OpenArchive(archive_);
  const ClipBounds clips = ClipBoundsOf(*reader);
  double constrained_share = 0;
  double unconstrained_share = 0;
  for (bool constrained : {true, false}) {
    const MotionGraph graph = Graph(*reader, constrained);
    uint64_t in_style = 0;
    uint64_t total = 0;
    for (uint64_t seed = 1; seed <= 10; ++seed) {
      WalkOptions options;
      options.frames = 30 * 120;
      options.seed = seed;
      auto walk = RandomWalk(graph, clips, 0, options);
      ASSERT_TRUE(walk.ok()) << walk.status().ToString();
      for (const WalkPiece& piece : *walk) {
        total += piece.end - piece.start;
        if (StyleOf(*reader, piece.clip) == 0) in_style += piece.end - piece.start;
      }
    }
    (constrained ? constrained_share : unconstrained_share) =
        static_cast<double>(in_style) / static_cast<double>(total);
  }
  EXPECT_GT(constrained_share, 0.95) << "unconstrained " << unconstrained_share;
  EXPECT_LT(unconstrained_share, 0.9) << "constrained " << constrained_share;
  std::printf("share of the walks in the start's style: constrained %.3f, unconstrained %.3f\n",
              constrained_share, unconstrained_share);
}

TEST_F(TwoStylesTest, TheWalksRootIsContinuousAndItsBvhReadsBack) {
  auto reader = OpenArchive(archive_);
  const ClipBounds clips = ClipBoundsOf(*reader);
  const MotionGraph graph = Graph(*reader, false);
  WalkOptions options;
  options.frames = 10 * 120;
  auto pieces = RandomWalk(graph, clips, 0, options);
  ASSERT_TRUE(pieces.ok());
  ASSERT_GT(pieces->size(), 1u);
  auto walk = WalkTake(*reader, *pieces, 30);
  ASSERT_TRUE(walk.ok()) << walk.status().ToString();
  EXPECT_EQ(walk->frame_count(), options.frames);
  // The clips stand still: the root never moves, whatever the junctions.
  for (size_t frame = 1; frame < walk->frame_count(); ++frame) {
    EXPECT_LT((walk->root_positions[frame] - walk->root_positions[frame - 1]).norm(), 1e-6)
        << frame;
  }
  const std::string bvh = dir_->File("walk.bvh");
  ASSERT_TRUE(WriteBvh(*walk, bvh).ok());
  // A reader the project did not write: three.js's BVHLoader under Node
  // (tests/engine/graph/bvh_three_check.mjs), when it is installed.
  const char* npm = std::getenv("MOTIF_NPM_DIR");
  const std::string modules = npm ? std::string(npm) : std::string(MOTIF_NPM_DIR);
  if (std::system("node --version > /dev/null 2>&1") != 0 ||
      !std::filesystem::exists(modules + "/node_modules/three/examples/jsm/loaders/BVHLoader.js")) {
    GTEST_SKIP() << "three.js's BVHLoader is not installed under " << modules
                 << " (scripts/build.sh installs it with npm when Node is present)";
  }
  const std::string out = dir_->File("three.json");
  const std::string command = "node " + std::string(MOTIF_SOURCE_DIR) +
                              "/tests/engine/graph/bvh_three_check.mjs " + modules + " " + bvh +
                              " > " + out;
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(out);
  std::string frames, bones;
  in >> frames >> bones;
  EXPECT_EQ(frames, "frames=" + std::to_string(options.frames));
  EXPECT_EQ(bones, "bones=" + std::to_string(kJoints));
}

}  // namespace
}  // namespace motif::testing
