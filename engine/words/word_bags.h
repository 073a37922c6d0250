// Windows of motion words compared as bags of their words (docs/design/signatures.md,
// "Segmentation"): the signature of a window with every word its own bin, each of unit mass, and
// the Earth Mover's Distance between two such signatures with the DTW between words
// (word_distance.h) as the ground distance. It is the paper's TF-IDF motif signature (tf_idf.h)
// in the limit of one motif per word: the words are not quantised to the nearest of k motifs,
// the idf is then the same for every bin, and the ground distance is the exact word distance that
// the embedding is trained to approximate. With unit masses and windows of n words each, the EMD
// is the mean DTW of the cheapest one-to-one matching of the two windows' words, in any order.
//
//  * WordsOfClips: every word of some clips, prepared for the DTW (about 7.7 KB a word at the
//    CMU skeleton's 12 weighted joints and 16-frame words).
//  * WordBagGround: the DTW between a run of words of one take and every word of a WordsOfClips,
//    as floats; the caller keeps the run short (a block of windows), so memory stays bounded.
//  * WordBagDistance: the EMD between a window of the run and a window of the references.
// Thread-safety: WordsOfClips and WordBagGround are immutable once built; a WordBagDistance
// keeps scratch buffers (one per task).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/status.h"
#include "engine/signature/earth_movers_distance.h"
#include "engine/signature/word_distance.h"
#include "engine/signature/word_grid.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

class WordsOfClips {
 public:
  // The words of `clips` (any order, no duplicates) cut with `words` from `reader`'s archive,
  // each prepared for `distance`. `joint_weights`: one per archive joint (LoadDistanceWeights),
  // selecting the weighted joints `distance` was made for. Errors of reading pass through;
  // InvalidArgument when a clip is out of range or the weights disagree with `distance`.
  static Result<WordsOfClips> Read(const FrameFileReader& reader,
                                   const std::vector<float>& joint_weights,
                                   const WordOptions& words, const WordDistance& distance,
                                   const std::vector<uint32_t>& clips);

  // Word `word` of clip `clip` (which must be one of the clips read, word < its word count).
  const PreparedWord& word(uint32_t clip, uint64_t word) const;
  // Index of that word among all words read (clips in the order given, words in order).
  uint64_t index(uint32_t clip, uint64_t word) const;
  // Whether clip `clip` is one of the clips read.
  bool holds(uint32_t clip) const {
    return clip < first_of_clip_.size() && first_of_clip_[clip] != UINT64_MAX;
  }
  uint64_t size() const { return words_.size(); }
  const PreparedWord& at(uint64_t index) const { return words_[index]; }

 private:
  std::vector<PreparedWord> words_;
  std::vector<uint64_t> first_of_clip_;  // per archive clip: index of its first word, or UINT64_MAX
};

// The DTW between words [first, end) of clip `clip` of `queries` and every word of `references`,
// computed in parallel in `threads` (0: all cores); each value is one WordDistance::Dtw, so the
// result does not depend on the thread count.
class WordBagGround {
 public:
  static WordBagGround Compute(const WordsOfClips& queries, uint32_t clip, uint64_t first,
                               uint64_t end, const WordsOfClips& references,
                               const WordDistance& distance, int threads);

  uint32_t clip() const { return clip_; }
  uint64_t first() const { return first_; }
  uint64_t end() const { return end_; }
  // DTW between query word `word` (in [first, end)) and reference word `reference_index`.
  float at(uint64_t word, uint64_t reference_index) const {
    return distances_(static_cast<Eigen::Index>(word - first_),
                      static_cast<Eigen::Index>(reference_index));
  }

 private:
  uint32_t clip_ = 0;
  uint64_t first_ = 0;
  uint64_t end_ = 0;
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> distances_;
};

class WordBagDistance {
 public:
  // The EMD between words [query_first, query_end) of the ground's take (within its run) and
  // words [reference_first, reference_end) of reference clip `reference_clip`, each word of unit
  // mass. InvalidArgument: an empty window.
  Result<double> Distance(const WordBagGround& ground, uint64_t query_first, uint64_t query_end,
                          const WordsOfClips& references, uint32_t reference_clip,
                          uint64_t reference_first, uint64_t reference_end);

 private:
  EarthMoversDistance emd_;
  std::vector<double> from_;
  std::vector<double> to_;
  Eigen::MatrixXd costs_;
};

}  // namespace motif
