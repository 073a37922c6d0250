// Labelling the words of takes by the windows around them (Aristidou et al. 2018, "Temporal
// Motion Segmentation"): each word is described by the window of `window` consecutive words
// centred on it, and takes the majority label of the k nearest windows of labelled takes (the
// kNN rule of take_retrieval.h, MajorityOfNearest). Overlapping windows of one take are near
// copies of each other, so the k nearest windows are mostly one take's; `one_per_take` votes
// with the k nearest takes instead, each at its nearest window (docs/design/signatures.md,
// "Segmentation", has both measured). Neighbouring words with equal labels then
// merge into segments. The distance between two windows is the caller's (the EMD between their
// signatures, or DTW over their frames), so the same vote serves signatures and the baseline.
// Thread-safety: pure functions; VoteWindows runs in its own task_arena over fixed blocks of
// queries, each query's vote depending on nothing else, so the labels do not depend on the
// thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "common/status.h"

namespace motif {

// [start, start + window): `window` words from word `first` (which may lie before 0), shifted
// inward to fit a take of `words` words; the whole take when it has fewer. Precondition:
// window >= 1.
std::pair<uint64_t, uint64_t> WindowFrom(int64_t first, uint64_t words, uint32_t window);

// [first, end): the `window` words centred on word `word` of a take of `words` words, i.e.
// [word - window / 2, word - window / 2 + window), shifted inward at the take's ends so that it
// keeps `window` words; the whole take when it has fewer. Precondition: word < words, window >= 1.
std::pair<uint64_t, uint64_t> CentredWindow(uint64_t word, uint64_t words, uint32_t window);

// The distance between query window q and reference window r. One is made per task (it may hold
// scratch buffers).
using WindowDistance = std::function<Result<double>(size_t query, size_t reference)>;
using WindowDistanceMaker = std::function<WindowDistance()>;

struct WindowVoteInput {
  uint32_t take_count = 0;  // takes are numbered 0 .. take_count - 1
  bool one_per_take = false;
  std::vector<uint32_t> query_takes;       // the take of each query window
  std::vector<uint32_t> reference_takes;   // the take of each reference window
  std::vector<uint32_t> reference_labels;  // its label, < label_count
  uint32_t label_count = 0;
  uint32_t k = 5;
};

// The label of every query window: the majority of its k nearest reference windows, or with
// one_per_take of its k nearest takes, each at its nearest window (nearest first; ties to the
// lower reference index), among those of other takes: a take never votes for itself. kUnlabelled
// for a query with no reference of another take. InvalidArgument: k 0, sizes that disagree, a take
// >= take_count, a label >= label_count; errors of the distance pass through (the first, by query).
// `progress(done, total)` counts queries.
Result<std::vector<uint32_t>> VoteWindows(
    const WindowVoteInput& input, const WindowDistanceMaker& make_distance, int threads,
    const std::function<void(uint64_t, uint64_t)>& progress = nullptr);

struct LabelledSegment {
  uint64_t start = 0;  // clip frames, end exclusive
  uint64_t end = 0;
  uint32_t label = 0;
  uint64_t first_word = 0;  // the words merged into it: [first_word, end_word)
  uint64_t end_word = 0;
};

// Merges runs of equal labels of a take's words into segments covering the whole take: the
// boundary between words i and i + 1 is the frame halfway between their centres (rounded
// down), the first segment starts at frame 0 and the last ends at `frame_count`.
// `word_centres[i]` (clip frames, non-decreasing) per word. Precondition (checked): as many
// centres as labels, at least one word, centres below frame_count.
std::vector<LabelledSegment> MergeLabels(const std::vector<uint32_t>& labels,
                                         const std::vector<double>& word_centres,
                                         uint64_t frame_count);

}  // namespace motif
