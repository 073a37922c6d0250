#include "engine/graph/motion_graph.h"

#include <gtest/gtest.h>

namespace motif::testing {
namespace {

constexpr uint32_t kWindow = 30;

// Clips A [0, 1000), B [1000, 2000), C [2000, 3000). A and B lead into each other; C leads into
// A, but nothing leads back into C.
struct ThreeClips {
  ClipBounds clips{{0, 1000, 2000, 3000}};
  std::vector<GraphTransition> transitions = {
      {{500, 1200, 0.1f}},  // A 500 -> B 1200 (arrives at 1230)
      {{1800, 100, 0.2f}},  // B 1800 -> A 100 (arrives at 130)
      {{2400, 600, 0.3f}},  // C 2400 -> A 600 (arrives at 630)
  };
};

TEST(MotionGraph, NodesAreClipStartsSourcesAndArrivals) {
  ThreeClips c;
  const MotionGraph graph = BuildMotionGraph(c.clips, c.transitions, kWindow);
  EXPECT_EQ(graph.nodes, (std::vector<uint64_t>{0, 130, 500, 630, 1000, 1230, 1800, 2000, 2400}));
  EXPECT_EQ(graph.NodeAt(1230), 5u);
  EXPECT_EQ(graph.NodeAt(1231), UINT32_MAX);
}

TEST(MotionGraph, ComponentsAreClosedAndATransitionOutOfThemIsPruned) {
  ThreeClips c;
  const MotionGraph graph = BuildMotionGraph(c.clips, c.transitions, kWindow);
  // The cycle A 130 -> 500 -> B 1230 -> 1800 -> A 130 is one component; A 630, the clip starts
  // and C's nodes are alone (C 2400 leads out and nothing comes back; A 630 only goes on to the
  // end of A).
  ASSERT_EQ(graph.component_sizes, std::vector<uint64_t>{4});
  const std::vector<int32_t> expected = {-1, 0, 0, -1, -1, 0, 0, -1, -1};
  EXPECT_EQ(graph.component, expected);
  EXPECT_EQ(graph.transitions[0].fate, TransitionFate::kKept);
  EXPECT_EQ(graph.transitions[1].fate, TransitionFate::kKept);
  EXPECT_EQ(graph.transitions[2].fate, TransitionFate::kComponent);
  EXPECT_EQ(graph.leaving[2], std::vector<uint32_t>{0});
  EXPECT_TRUE(graph.leaving[8].empty());
  // A transition already pruned (by its signature) adds no node and no edge, and keeps its fate.
  c.transitions[1].fate = TransitionFate::kSignature;
  const MotionGraph broken = BuildMotionGraph(c.clips, c.transitions, kWindow);
  EXPECT_TRUE(broken.component_sizes.empty());
  EXPECT_EQ(broken.transitions[1].fate, TransitionFate::kSignature);
  EXPECT_EQ(broken.transitions[0].fate, TransitionFate::kComponent);
}

TEST(MotionGraph, AWalkStaysInItsComponentAndPlaysTheFramesAskedFor) {
  ThreeClips c;
  const MotionGraph graph = BuildMotionGraph(c.clips, c.transitions, kWindow);
  WalkOptions options;
  options.frames = 5000;
  options.min_piece_frames = 0;
  for (uint64_t seed : {1, 2, 3}) {
    options.seed = seed;
    auto walk = RandomWalk(graph, c.clips, 0, options);
    ASSERT_TRUE(walk.ok()) << walk.status().ToString();
    EXPECT_EQ(WalkFrames(*walk, kWindow), 5000u);
    // From A's first node in the component, 130; every piece is [130, 530) of A or
    // [1200 - 1000, 1830 - 1000) of B, but the last, which is cut.
    EXPECT_EQ((*walk)[0].clip, 0u);
    EXPECT_EQ((*walk)[0].start, 130u);
    for (size_t idx = 0; idx + 1 < walk->size(); ++idx) {
      const WalkPiece& piece = (*walk)[idx];
      EXPECT_EQ(piece.clip, idx % 2 == 0 ? 0u : 1u);
      if (idx > 0) {
        EXPECT_EQ(piece.start, piece.clip == 0 ? 100u : 200u);
      }
      EXPECT_EQ(piece.end, piece.clip == 0 ? 530u : 830u);
    }
    auto again = RandomWalk(graph, c.clips, 0, options);
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(WalkFrames(*again, kWindow), 5000u);
    ASSERT_EQ(again->size(), walk->size());
    for (size_t idx = 0; idx < walk->size(); ++idx) EXPECT_EQ((*again)[idx].end, (*walk)[idx].end);
  }
  // C has no node in a component: an error naming why.
  auto from_c = RandomWalk(graph, c.clips, 2, options);
  EXPECT_TRUE(from_c.status().IsInvalidArgument());
  EXPECT_NE(from_c.status().message().find("strongly connected"), std::string::npos);
}

TEST(MotionGraph, AfterATransitionTheWalkPlaysTheMinimumPieceBeforeTheNext) {
  // Two transitions leave A, at 200 and 600, into B; B comes back from 1500 and 1900. Arriving
  // at A 180 (from B 1500), the walk passes the exit at 200 (20 frames played) and may take the
  // one at 600. Every exit is at least 240 frames after the arrivals before it, so no piece is
  // forced out early by a clip with no node further on.
  ClipBounds clips{{0, 1000, 2000}};
  std::vector<GraphTransition> transitions = {
      {{200, 1100, 0}}, {{600, 1400, 0}}, {{1500, 150, 0}}, {{1900, 250, 0}}};
  const MotionGraph graph = BuildMotionGraph(clips, transitions, kWindow);
  WalkOptions options;
  options.frames = 20000;
  options.min_piece_frames = 240;
  options.seed = 7;
  auto walk = RandomWalk(graph, clips, 0, options);
  ASSERT_TRUE(walk.ok());
  ASSERT_GT(walk->size(), 4u);
  for (size_t idx = 1; idx + 1 < walk->size(); ++idx) {
    EXPECT_GE((*walk)[idx].end - (*walk)[idx].start, 240u + 2 * kWindow)
        << "piece " << idx << " [" << (*walk)[idx].start << ", " << (*walk)[idx].end << ")";
  }
}

}  // namespace
}  // namespace motif::testing
