#include "engine/words/window_vote.h"

#include <gtest/gtest.h>

#include "engine/signature/take_retrieval.h"

namespace motif::testing {
namespace {

TEST(WindowVote, CentredWindowsKeepTheirSizeAndShiftInwardAtTheEnds) {
  using Range = std::pair<uint64_t, uint64_t>;
  EXPECT_EQ(CentredWindow(0, 20, 9), Range(0, 9));
  EXPECT_EQ(CentredWindow(4, 20, 9), Range(0, 9));
  EXPECT_EQ(CentredWindow(5, 20, 9), Range(1, 10));
  EXPECT_EQ(CentredWindow(10, 20, 9), Range(6, 15));
  EXPECT_EQ(CentredWindow(15, 20, 9), Range(11, 20));
  EXPECT_EQ(CentredWindow(19, 20, 9), Range(11, 20));
  EXPECT_EQ(CentredWindow(2, 5, 9), Range(0, 5));  // a take shorter than the window
  EXPECT_EQ(CentredWindow(3, 9, 9), Range(0, 9));
  EXPECT_EQ(CentredWindow(3, 10, 4), Range(1, 5));  // even: two words before, one after
}

// Queries and references on a line: the distance is |position difference|.
struct LineCase {
  std::vector<double> query_at;
  std::vector<double> reference_at;
  WindowVoteInput input;
  WindowDistanceMaker Maker() const {
    return [this] {
      return WindowDistance([this](size_t q, size_t r) -> Result<double> {
        return std::abs(query_at[q] - reference_at[r]);
      });
    };
  }
};

TEST(WindowVote, EachQueryTakesTheMajorityOfItsNearestWindowsOfOtherTakes) {
  LineCase c;
  // Take 0 (label 0) at 0..2, take 1 (label 1) at 10..12, take 2 (label 0) at 20, 21.
  c.reference_at = {0, 1, 2, 10, 11, 12, 20, 21};
  c.input.reference_takes = {0, 0, 0, 1, 1, 1, 2, 2};
  c.input.reference_labels = {0, 0, 0, 1, 1, 1, 0, 0};
  c.input.label_count = 2;
  c.input.take_count = 4;
  c.input.k = 3;
  // Query take 3 at 1 (near take 0), at 11 (near take 1), at 16 (2 of take 1 and 1 of take 2
  // within 5: label 1). Query of take 0 at 1: its own windows are left out, so 10, 11, 12 vote.
  c.query_at = {1, 11, 16, 1};
  c.input.query_takes = {3, 3, 3, 0};
  for (int threads : {1, 2}) {
    auto labels = VoteWindows(c.input, c.Maker(), threads);
    ASSERT_TRUE(labels.ok()) << labels.status().ToString();
    EXPECT_EQ(*labels, (std::vector<uint32_t>{0, 1, 1, 1}));
  }
}

TEST(WindowVote, OnePerTakeVotesWithTheNearestTakes) {
  LineCase c;
  // Take 0 (label 1) has three windows right at the query; takes 1 and 2 (label 0) one each a
  // little farther. By windows the 3 nearest are take 0's: label 1. By takes: 0, 1, 2: label 0.
  c.reference_at = {0, 0.1, 0.2, 1, 1.5};
  c.input.reference_takes = {0, 0, 0, 1, 2};
  c.input.reference_labels = {1, 1, 1, 0, 0};
  c.input.label_count = 2;
  c.input.take_count = 4;
  c.input.k = 3;
  c.query_at = {0};
  c.input.query_takes = {3};
  EXPECT_EQ(*VoteWindows(c.input, c.Maker(), 1), std::vector<uint32_t>{1});
  c.input.one_per_take = true;
  EXPECT_EQ(*VoteWindows(c.input, c.Maker(), 1), std::vector<uint32_t>{0});
}

TEST(WindowVote, ATieGoesToTheNearerLabelAndAQueryWithNoOtherTakeHasNone) {
  LineCase c;
  c.reference_at = {5, 3, 10, 12};
  c.input.reference_takes = {0, 1, 2, 2};
  c.input.reference_labels = {0, 1, 2, 2};
  c.input.label_count = 3;
  c.input.take_count = 3;
  c.input.k = 2;
  // Queries of take 2 at 3.8 and 4.2: the two nearest others are 3 (label 1) and 5 (label 0),
  // one vote each: the nearer wins. Query of take 0 at 5: 3 (label 1) and 10 (label 2): 1.
  c.query_at = {3.8, 4.2, 5};
  c.input.query_takes = {2, 2, 0};
  EXPECT_EQ(*VoteWindows(c.input, c.Maker(), 1), (std::vector<uint32_t>{1, 0, 1}));
  // Only take 0 has references: its own query gets no label.
  c.input.reference_takes = {0};
  c.input.reference_labels = {0};
  c.reference_at = {5};
  c.query_at = {5};
  c.input.query_takes = {0};
  EXPECT_EQ(*VoteWindows(c.input, c.Maker(), 1), std::vector<uint32_t>{kUnlabelled});
}

TEST(WindowVote, BadInputAndDistanceErrorsAreReported) {
  LineCase c;
  c.reference_at = {0};
  c.input.reference_takes = {0};
  c.input.reference_labels = {2};
  c.input.label_count = 2;
  c.input.take_count = 2;
  c.query_at = {0};
  c.input.query_takes = {1};
  EXPECT_TRUE(VoteWindows(c.input, c.Maker(), 1).status().IsInvalidArgument());
  c.input.reference_labels = {0};
  c.input.k = 0;
  EXPECT_TRUE(VoteWindows(c.input, c.Maker(), 1).status().IsInvalidArgument());
  c.input.k = 1;
  WindowDistanceMaker failing = [] {
    return WindowDistance(
        [](size_t, size_t) -> Result<double> { return Status::InvalidArgument("no mass"); });
  };
  const Status status = VoteWindows(c.input, failing, 1).status();
  EXPECT_TRUE(status.IsInvalidArgument());
  EXPECT_NE(status.message().find("no mass"), std::string::npos);
}

TEST(WindowVote, EqualNeighbouringLabelsMergeHalfwayBetweenWordCentres) {
  const std::vector<double> centres = {10, 30, 50, 70, 90, 110};
  const auto segments = MergeLabels({0, 0, 1, 1, 1, 0}, centres, 130);
  ASSERT_EQ(segments.size(), 3u);
  EXPECT_EQ(segments[0].start, 0u);
  EXPECT_EQ(segments[0].end, 40u);
  EXPECT_EQ(segments[0].label, 0u);
  EXPECT_EQ(segments[1].start, 40u);
  EXPECT_EQ(segments[1].end, 100u);
  EXPECT_EQ(segments[1].label, 1u);
  EXPECT_EQ(segments[1].first_word, 2u);
  EXPECT_EQ(segments[1].end_word, 5u);
  EXPECT_EQ(segments[2].start, 100u);
  EXPECT_EQ(segments[2].end, 130u);
  EXPECT_EQ(segments[2].label, 0u);
  // One label: one segment over the whole take; a half-frame boundary rounds down.
  EXPECT_EQ(MergeLabels({4, 4}, {10, 30}, 50).size(), 1u);
  EXPECT_EQ(MergeLabels({0, 1}, {10, 31}, 50)[1].start, 20u);
}

}  // namespace
}  // namespace motif::testing
