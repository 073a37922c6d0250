#include "engine/words/word_bags.h"

#include <algorithm>
#include <memory>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engine/signature/word_stream.h"

namespace motif {
namespace {

// The clips as runs of consecutive archive clips, [first, end), so each run is one stream.
std::vector<std::pair<uint32_t, uint32_t>> ClipRuns(std::vector<uint32_t> clips) {
  std::sort(clips.begin(), clips.end());
  std::vector<std::pair<uint32_t, uint32_t>> runs;
  for (uint32_t clip : clips) {
    if (!runs.empty() && runs.back().second == clip) {
      ++runs.back().second;
    } else {
      runs.emplace_back(clip, clip + 1);
    }
  }
  return runs;
}

}  // namespace

Result<WordsOfClips> WordsOfClips::Read(const FrameFileReader& reader,
                                        const std::vector<float>& joint_weights,
                                        const WordOptions& words, const WordDistance& distance,
                                        const std::vector<uint32_t>& clips) {
  const size_t clip_count = reader.clips().size();
  WordsOfClips result;
  result.first_of_clip_.assign(clip_count, UINT64_MAX);
  // Word indices follow the clips in the order given; the streams read them in archive order.
  uint64_t next = 0;
  for (uint32_t clip : clips) {
    if (clip >= clip_count) {
      return Status::InvalidArgument("word bags: clip index " + std::to_string(clip) +
                                     " out of range");
    }
    result.first_of_clip_[clip] = next;
    next += ClipWordGrid(reader, clip, words).word_count();
  }
  result.words_.resize(next);
  for (const auto& [first, end] : ClipRuns(clips)) {
    WordStreamOptions options;
    options.words = words;
    options.first_clip = first;
    options.clip_count = end - first;
    MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<WordStream> stream,
                           WordStream::Create(reader, joint_weights, options));
    WordBatch batch;
    for (;;) {
      MOTIF_ASSIGN_OR_RETURN(bool more, stream->Next(&batch));
      if (!more) break;
      if (batch.word_values() != words.word_frames * distance.feature_values()) {
        return Status::InvalidArgument(
            "word bags: the joint weights select other joints than the word distance's " +
            std::to_string(distance.weights().size()));
      }
      for (size_t w = 0; w < batch.size(); ++w) {
        const WordInfo& info = batch.info(w);
        distance.Prepare(batch.word(w), &result.words_[result.index(info.clip_idx, info.word_idx)]);
      }
    }
  }
  return result;
}

uint64_t WordsOfClips::index(uint32_t clip, uint64_t word) const {
  MOTIF_CHECK(holds(clip));
  return first_of_clip_[clip] + word;
}

const PreparedWord& WordsOfClips::word(uint32_t clip, uint64_t word) const {
  return words_[index(clip, word)];
}

WordBagGround WordBagGround::Compute(const WordsOfClips& queries, uint32_t clip, uint64_t first,
                                     uint64_t end, const WordsOfClips& references,
                                     const WordDistance& distance, int threads) {
  MOTIF_CHECK(first <= end);
  WordBagGround ground;
  ground.clip_ = clip;
  ground.first_ = first;
  ground.end_ = end;
  ground.distances_.resize(static_cast<Eigen::Index>(end - first),
                           static_cast<Eigen::Index>(references.size()));
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint64_t>(first, end), [&](const auto& rows) {
      for (uint64_t word = rows.begin(); word != rows.end(); ++word) {
        const PreparedWord& query = queries.word(clip, word);
        for (uint64_t reference = 0; reference < references.size(); ++reference) {
          ground.distances_(static_cast<Eigen::Index>(word - first),
                            static_cast<Eigen::Index>(reference)) =
              static_cast<float>(distance.Dtw(query, references.at(reference)));
        }
      }
    });
  });
  return ground;
}

Result<double> WordBagDistance::Distance(const WordBagGround& ground, uint64_t query_first,
                                         uint64_t query_end, const WordsOfClips& references,
                                         uint32_t reference_clip, uint64_t reference_first,
                                         uint64_t reference_end) {
  MOTIF_CHECK(ground.first() <= query_first && query_end <= ground.end());
  const uint64_t from = query_end - query_first;
  const uint64_t to = reference_end - reference_first;
  if (from == 0 || to == 0) return Status::InvalidArgument("word bags: an empty window");
  // Bins 0 .. from - 1 are the query's words, from .. from + to - 1 the reference's; only the
  // costs from the first to the second are read.
  const auto bins = static_cast<Eigen::Index>(from + to);
  from_.assign(static_cast<size_t>(bins), 0.0);
  to_.assign(static_cast<size_t>(bins), 0.0);
  costs_.setZero(bins, bins);
  const uint64_t reference_base = references.index(reference_clip, reference_first);
  for (uint64_t a = 0; a < from; ++a) {
    from_[a] = 1;
    for (uint64_t b = 0; b < to; ++b) {
      costs_(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(from + b)) =
          ground.at(query_first + a, reference_base + b);
    }
  }
  for (uint64_t b = 0; b < to; ++b) to_[from + b] = 1;
  return emd_.Distance(from_, to_, costs_);
}

}  // namespace motif
