#include "engine/words/window_vote.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engine/signature/take_retrieval.h"

namespace motif {
namespace {

constexpr size_t kQueriesPerTask = 16;

Status CheckInput(const WindowVoteInput& input) {
  if (input.k == 0) return Status::InvalidArgument("the kNN vote needs k >= 1");
  if (input.reference_takes.size() != input.reference_labels.size()) {
    return Status::InvalidArgument("reference windows and their labels differ in number");
  }
  for (uint32_t take : input.reference_takes) {
    if (take >= input.take_count) {
      return Status::InvalidArgument("a reference take out of range: " + std::to_string(take));
    }
  }
  for (uint32_t label : input.reference_labels) {
    if (label >= input.label_count) {
      return Status::InvalidArgument("a reference label out of range: " + std::to_string(label));
    }
  }
  return Status::Ok();
}

// The vote of query `query`: its k nearest windows of other takes, or with `one_per_take` its
// k nearest other takes, each at its nearest window. Ties: the lower reference index.
Result<uint32_t> VoteOne(const WindowVoteInput& input, size_t query, WindowDistance& distance,
                         std::vector<std::pair<double, size_t>>& nearest) {
  nearest.clear();
  std::vector<size_t> slot_of_take(input.one_per_take ? input.take_count : 0, SIZE_MAX);
  for (size_t reference = 0; reference < input.reference_takes.size(); ++reference) {
    const uint32_t take = input.reference_takes[reference];
    if (take == input.query_takes[query]) continue;
    MOTIF_ASSIGN_OR_RETURN(const double value, distance(query, reference));
    if (!input.one_per_take) {
      nearest.emplace_back(value, reference);
    } else if (slot_of_take[take] == SIZE_MAX) {
      slot_of_take[take] = nearest.size();
      nearest.emplace_back(value, reference);
    } else if (value < nearest[slot_of_take[take]].first) {
      nearest[slot_of_take[take]] = {value, reference};
    }
  }
  const size_t k = std::min<size_t>(input.k, nearest.size());
  std::partial_sort(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(k),
                    nearest.end());
  std::vector<uint32_t> labels;
  for (size_t idx = 0; idx < k; ++idx)
    labels.push_back(input.reference_labels[nearest[idx].second]);
  return MajorityOfNearest(labels, input.label_count);
}

}  // namespace

std::pair<uint64_t, uint64_t> WindowFrom(int64_t first, uint64_t words, uint32_t window) {
  MOTIF_CHECK(window >= 1);
  if (words <= window) return {0, words};
  const auto start =
      static_cast<uint64_t>(std::clamp<int64_t>(first, 0, static_cast<int64_t>(words - window)));
  return {start, start + window};
}

std::pair<uint64_t, uint64_t> CentredWindow(uint64_t word, uint64_t words, uint32_t window) {
  MOTIF_CHECK(word < words && window >= 1);
  return WindowFrom(static_cast<int64_t>(word) - static_cast<int64_t>(window / 2), words, window);
}

Result<std::vector<uint32_t>> VoteWindows(const WindowVoteInput& input,
                                          const WindowDistanceMaker& make_distance, int threads,
                                          const std::function<void(uint64_t, uint64_t)>& progress) {
  MOTIF_RETURN_IF_ERROR(CheckInput(input));
  const size_t queries = input.query_takes.size();
  std::vector<uint32_t> labels(queries, kUnlabelled);
  std::vector<Status> failures(queries);
  std::atomic<uint64_t> done{0};
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, queries, kQueriesPerTask),
        [&](const tbb::blocked_range<size_t>& range) {
          WindowDistance distance = make_distance();
          std::vector<std::pair<double, size_t>> nearest;
          for (size_t query = range.begin(); query != range.end(); ++query) {
            Result<uint32_t> label = VoteOne(input, query, distance, nearest);
            if (!label.ok()) {
              failures[query] = label.status();
              return;
            }
            labels[query] = *label;
          }
          const uint64_t now = done.fetch_add(range.size()) + range.size();
          if (progress) progress(now, queries);
        },
        tbb::simple_partitioner());
  });
  for (const Status& failure : failures) MOTIF_RETURN_IF_ERROR(failure);
  return labels;
}

std::vector<LabelledSegment> MergeLabels(const std::vector<uint32_t>& labels,
                                         const std::vector<double>& word_centres,
                                         uint64_t frame_count) {
  MOTIF_CHECK(!labels.empty() && labels.size() == word_centres.size());
  MOTIF_CHECK(word_centres.back() < static_cast<double>(frame_count));
  std::vector<LabelledSegment> segments;
  LabelledSegment current{0, frame_count, labels[0], 0, 1};
  for (size_t word = 1; word < labels.size(); ++word) {
    if (labels[word] == current.label) {
      current.end_word = word + 1;
      continue;
    }
    const auto boundary =
        static_cast<uint64_t>(std::floor((word_centres[word - 1] + word_centres[word]) / 2));
    current.end = boundary;
    segments.push_back(current);
    current = LabelledSegment{boundary, frame_count, labels[word], word, word + 1};
  }
  segments.push_back(current);
  return segments;
}

}  // namespace motif
