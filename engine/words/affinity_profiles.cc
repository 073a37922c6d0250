#include "engine/words/affinity_profiles.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engine/words/signature_change.h"

namespace motif {
namespace {

using FloatRows = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

template <typename Body>
void ParallelRows(uint64_t rows, int threads, Body&& body) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, rows), [&](const auto& range) {
      for (uint64_t row = range.begin(); row != range.end(); ++row) body(row);
    });
  });
}

// The words of the columns: all, or kMaxProfileColumns of them spread evenly.
std::vector<uint64_t> ColumnWords(uint64_t words) {
  const uint64_t columns = std::min(words, kMaxProfileColumns);
  std::vector<uint64_t> chosen(columns);
  for (uint64_t c = 0; c < columns; ++c) chosen[c] = c * words / columns;
  return chosen;
}

// The DTW to the k-th nearest of the `columns` DTWs in `dtw` other than column `self` (-1:
// none is itself); the farthest when there are fewer; 0 when there is no other.
float LocalScale(const float* dtw, Eigen::Index columns, int64_t self) {
  std::vector<float> others;
  for (Eigen::Index c = 0; c < columns; ++c) {
    if (c != self) others.push_back(dtw[c]);
  }
  if (others.empty()) return 0;
  const size_t k = std::min<size_t>(kProfileScaleNeighbour, others.size()) - 1;
  std::nth_element(others.begin(), others.begin() + static_cast<std::ptrdiff_t>(k), others.end());
  return others[k];
}

// The DTWs between every two column words (`column_words` index `index`, itself into `words`).
FloatRows BetweenColumns(const WordsOfClips& words, const std::vector<uint64_t>& index,
                         const std::vector<uint64_t>& column_words, const WordDistance& distance,
                         int threads) {
  const auto columns = static_cast<Eigen::Index>(column_words.size());
  FloatRows between(columns, columns);
  ParallelRows(column_words.size(), threads, [&](uint64_t c) {
    for (Eigen::Index d = 0; d < columns; ++d) {
      between(static_cast<Eigen::Index>(c), d) =
          c == static_cast<uint64_t>(d)
              ? 0.0f
              : static_cast<float>(distance.Dtw(words.at(index[column_words[c]]),
                                                words.at(index[column_words[d]])));
    }
  });
  return between;
}

double Affinity(float dtw, float scale_a, float scale_b) {
  const double scales = static_cast<double>(scale_a) * scale_b;
  if (scales <= 0) return dtw <= 0 ? 1.0 : 0.0;
  return std::exp(-static_cast<double>(dtw) * dtw / scales);
}

}  // namespace

AffinityProfiles AffinityProfiles::Compute(
    const WordsOfClips& words, const std::vector<uint32_t>& clips,
    const std::vector<uint64_t>& clip_words, const WordDistance& distance, int threads,
    const std::function<void(uint64_t, uint64_t)>& progress) {
  // Every word in clip order: row r of the profiles is word index[r] of `words`.
  std::vector<uint64_t> index;
  AffinityProfiles profiles;
  profiles.first_row_.assign(clip_words.size(), UINT64_MAX);
  for (uint32_t clip : clips) {
    profiles.first_row_[clip] = index.size();
    for (uint64_t word = 0; word < clip_words[clip]; ++word) {
      index.push_back(words.index(clip, word));
    }
  }
  const uint64_t n = index.size();
  const std::vector<uint64_t> column_words = ColumnWords(n);
  const auto columns = static_cast<Eigen::Index>(column_words.size());
  std::vector<int64_t> column_of(n, -1);
  for (size_t c = 0; c < column_words.size(); ++c) {
    column_of[column_words[c]] = static_cast<int64_t>(c);
  }
  // The DTWs between column words, kept (every word's, when all words are columns).
  const FloatRows between = BetweenColumns(words, index, column_words, distance, threads);
  std::vector<float> column_scale(column_words.size());
  for (size_t c = 0; c < column_words.size(); ++c) {
    column_scale[c] =
        LocalScale(&between(static_cast<Eigen::Index>(c), 0), columns, static_cast<int64_t>(c));
  }
  // Each word's profile.
  profiles.rows_.resize(static_cast<Eigen::Index>(n), columns);
  const auto profile_row = [&](uint64_t word) {
    std::vector<float> own;
    const float* dtw = nullptr;
    if (column_of[word] >= 0) {
      dtw = &between(static_cast<Eigen::Index>(column_of[word]), 0);
    } else {
      own.resize(column_words.size());
      for (size_t c = 0; c < column_words.size(); ++c) {
        own[c] = static_cast<float>(
            distance.Dtw(words.at(index[word]), words.at(index[column_words[c]])));
      }
      dtw = own.data();
    }
    const float scale = LocalScale(dtw, columns, column_of[word]);
    for (Eigen::Index c = 0; c < columns; ++c) {
      profiles.rows_(static_cast<Eigen::Index>(word), c) =
          static_cast<float>(Affinity(dtw[c], scale, column_scale[static_cast<size_t>(c)]));
    }
  };
  // In blocks, so progress is reported from this thread between them.
  constexpr uint64_t kProgressBlock = 512;
  for (uint64_t block = 0; block < n; block += kProgressBlock) {
    const uint64_t block_end = std::min(n, block + kProgressBlock);
    ParallelRows(block_end - block, threads, [&](uint64_t offset) {
      profile_row(block + offset);
    });
    if (progress) progress(block_end, n);
  }
  return profiles;
}

Eigen::VectorXd AffinityProfiles::Mean(const WordRange& range) const {
  MOTIF_CHECK(range.clip < first_row_.size() && first_row_[range.clip] != UINT64_MAX &&
              range.first < range.end);
  const auto first = static_cast<Eigen::Index>(first_row_[range.clip] + range.first);
  const auto count = static_cast<Eigen::Index>(range.end - range.first);
  // Summed in double, row by row, so a long stretch keeps the floats' precision.
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(rows_.cols());
  for (Eigen::Index row = first; row < first + count; ++row) {
    sum += rows_.row(row).transpose().cast<double>();
  }
  return sum / static_cast<double>(count);
}

double AffinityProfiles::Distance(const WordRange& a, const WordRange& b) const {
  return (Mean(a) - Mean(b)).norm();
}

std::vector<double> ProfileChangeScores(const AffinityProfiles& profiles, uint32_t clip,
                                        uint64_t words, uint32_t window) {
  return ChangeScores(words, window,
                      [&](uint64_t a_first, uint64_t a_end, uint64_t b_first, uint64_t b_end) {
                        return profiles.Distance({clip, a_first, a_end}, {clip, b_first, b_end});
                      });
}

Eigen::MatrixXd ProfilePieceDistances(const AffinityProfiles& profiles,
                                      const std::vector<WordRange>& pieces) {
  std::vector<Eigen::VectorXd> means;
  for (const WordRange& piece : pieces) means.push_back(profiles.Mean(piece));
  const auto n = static_cast<Eigen::Index>(pieces.size());
  Eigen::MatrixXd distances = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    for (Eigen::Index b = a + 1; b < n; ++b) {
      distances(a, b) = (means[static_cast<size_t>(a)] - means[static_cast<size_t>(b)]).norm();
      distances(b, a) = distances(a, b);
    }
  }
  return distances;
}

}  // namespace motif
