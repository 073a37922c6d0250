#include "engine/embedding/dtw_neighbours.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "common/split_mix64.h"
#include "engine/lsh/hash_family.h"
#include "engine/signature/k_means.h"
#include "engine/signature/word_distance.h"

namespace motif {
namespace {

constexpr uint32_t kDescriptorRuns = 4;
constexpr uint32_t kSamplePerList = 64;
constexpr uint32_t kMaxLists = 4096;

// The descriptors of every word (n x runs * 10 J_w).
RowMatrixXf Descriptors(const WordPool& pool, tbb::task_arena& arena) {
  const uint32_t frames = pool.word_frames();
  const uint32_t runs = std::min(kDescriptorRuns, frames);
  // The LSH's sign-free embedding of a frame; the hash tables drawn with it are not used.
  const HashFamily family = HashFamily::Draw(pool.joint_weights(), 1, 1, 1.0f, 0);
  const uint32_t dims = family.embedding_dims();
  const size_t feature_values = 4 * static_cast<size_t>(pool.weighted_joints());
  RowMatrixXf descriptors = RowMatrixXf::Zero(static_cast<Eigen::Index>(pool.size()), runs * dims);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, pool.size(), 256),
                      [&](const tbb::blocked_range<uint64_t>& range) {
                        std::vector<float> frame(dims);
                        for (uint64_t word = range.begin(); word != range.end(); ++word) {
                          float* out = descriptors.row(static_cast<Eigen::Index>(word)).data();
                          const int16_t* features = pool.features(word, 0);
                          std::vector<uint32_t> counts(runs, 0);
                          for (uint32_t f = 0; f < frames; ++f) {
                            const uint32_t run = f * runs / frames;
                            family.Embed(features + f * feature_values, frame.data());
                            for (uint32_t dim = 0; dim < dims; ++dim)
                              out[run * dims + dim] += frame[dim];
                            ++counts[run];
                          }
                          for (uint32_t run = 0; run < runs; ++run) {
                            for (uint32_t dim = 0; dim < dims; ++dim) {
                              out[run * dims + dim] /= static_cast<float>(counts[run]);
                            }
                          }
                        }
                      });
  });
  return descriptors;
}

// k-means centroids of a seeded sample of the descriptors; fewer lists when the words have fewer
// distinct descriptors than asked (k-means++ then runs out of points).
Result<RowMatrixXf> FitLists(const RowMatrixXf& descriptors, uint32_t lists, uint64_t seed,
                             int threads) {
  const uint64_t n = static_cast<uint64_t>(descriptors.rows());
  const uint64_t sample_size = std::min<uint64_t>(n, uint64_t{kSamplePerList} * lists);
  std::vector<uint64_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  SplitMix64 random(seed ^ 0x6976666c69737473ull);    // "ivflists"
  for (uint64_t idx = 0; idx < sample_size; ++idx) {  // partial Fisher-Yates
    std::swap(order[idx], order[idx + random.Below(n - idx)]);
  }
  std::sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(sample_size));
  RowMatrixXf sample(static_cast<Eigen::Index>(sample_size), descriptors.cols());
  for (uint64_t idx = 0; idx < sample_size; ++idx) {
    sample.row(static_cast<Eigen::Index>(idx)) =
        descriptors.row(static_cast<Eigen::Index>(order[idx]));
  }
  for (uint32_t k = std::min<uint64_t>(lists, sample_size); k >= 1; k = k / 2) {
    KMeansOptions options;
    options.k = k;
    options.seed = seed;
    options.max_iterations = 20;
    options.threads = threads;
    Result<KMeansResult> result = RunKMeans(sample, options);
    if (result.ok()) return std::move(result->centroids);
    if (k == 1) return result.status();
  }
  return Status::InvalidArgument("dtw neighbours: no lists");
}

uint32_t ListCount(const DtwNeighbourOptions& options, uint64_t words) {
  if (options.lists > 0) return options.lists;
  return static_cast<uint32_t>(
      std::clamp<double>(std::round(std::sqrt(static_cast<double>(words))), 1, kMaxLists));
}

// Inverted lists: the words of each list (their nearest centroid), in index order.
std::vector<std::vector<uint32_t>> InvertedLists(const RowMatrixXf& descriptors,
                                                 const RowMatrixXf& centroids,
                                                 tbb::task_arena& arena) {
  const uint64_t n = static_cast<uint64_t>(descriptors.rows());
  std::vector<uint32_t> list_of(n);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<uint64_t>(0, n, 1024), [&](const tbb::blocked_range<uint64_t>& range) {
          for (uint64_t word = range.begin(); word != range.end(); ++word) {
            list_of[word] =
                NearestCentroid(centroids, descriptors.row(static_cast<Eigen::Index>(word)).data());
          }
        });
  });
  std::vector<std::vector<uint32_t>> members(static_cast<size_t>(centroids.rows()));
  for (uint64_t word = 0; word < n; ++word)
    members[list_of[word]].push_back(static_cast<uint32_t>(word));
  return members;
}

// Every word prepared for the DTW once.
std::vector<PreparedWord> PrepareWords(const WordPool& pool, const WordDistance& distance,
                                       tbb::task_arena& arena) {
  const uint64_t n = pool.size();
  std::vector<PreparedWord> prepared(n);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, n, 1024),
                      [&](const tbb::blocked_range<uint64_t>& range) {
                        for (uint64_t word = range.begin(); word != range.end(); ++word) {
                          distance.Prepare(pool.features(word, 0), &prepared[word]);
                        }
                      });
  });
  return prepared;
}

// One word's neighbours: the words of the `probes` lists nearest its descriptor (not itself or
// the words overlapping it), the nearest `max_verified` of them by descriptor verified by DTW
// with early abandoning; the k nearest kept, by distance then word.
class DtwNeighbourSearch {
 public:
  DtwNeighbourSearch(const WordPool& pool, const DtwNeighbourOptions& options,
                     const RowMatrixXf& descriptors, const RowMatrixXf& centroids,
                     const std::vector<std::vector<uint32_t>>& members,
                     const WordDistance& distance, const std::vector<PreparedWord>& prepared)
      : pool_(pool),
        options_(options),
        descriptors_(descriptors),
        centroids_(centroids),
        members_(members),
        distance_(distance),
        prepared_(prepared),
        lists_(static_cast<uint32_t>(centroids.rows())),
        probes_(std::min(options.probes, lists_)) {}

  // Scratch of one thread.
  struct Scratch {
    std::vector<std::pair<float, uint32_t>> list_distances;
    std::vector<std::pair<float, uint32_t>> candidates;
  };

  void Find(uint64_t word, Scratch* scratch, std::vector<WordNeighbour>* best) const {
    ProbeCandidates(word, scratch);
    std::vector<std::pair<float, uint32_t>>& candidates = scratch->candidates;
    size_t verify = candidates.size();
    if (options_.max_verified > 0 && verify > options_.max_verified) {
      verify = options_.max_verified;
      std::partial_sort(candidates.begin(),
                        candidates.begin() + static_cast<std::ptrdiff_t>(verify), candidates.end());
    }
    for (size_t idx = 0; idx < verify; ++idx) Verify(word, candidates[idx].second, best);
  }

 private:
  // The candidates (descriptor distance, word) of the nearest lists, in probe order.
  void ProbeCandidates(uint64_t word, Scratch* scratch) const {
    std::vector<std::pair<float, uint32_t>>& list_distances = scratch->list_distances;
    list_distances.resize(lists_);
    const auto query = descriptors_.row(static_cast<Eigen::Index>(word));
    for (uint32_t list = 0; list < lists_; ++list) {
      list_distances[list] = {(centroids_.row(list) - query).squaredNorm(), list};
    }
    std::partial_sort(list_distances.begin(), list_distances.begin() + probes_,
                      list_distances.end());
    scratch->candidates.clear();
    const uint32_t clip = pool_.clip_of(word);
    const uint64_t index = pool_.index_in_clip(word);
    const uint32_t overlap = pool_.overlap_words();
    for (uint32_t probe = 0; probe < probes_; ++probe) {
      for (uint32_t other : members_[list_distances[probe].second]) {
        if (pool_.clip_of(other) == clip) {
          const uint64_t other_index = pool_.index_in_clip(other);
          const uint64_t gap = other_index > index ? other_index - index : index - other_index;
          if (gap < overlap) continue;  // itself and the words overlapping it
        }
        scratch->candidates.push_back({(descriptors_.row(other) - query).squaredNorm(), other});
      }
    }
  }

  // Inserts `other` into *best (sorted, at most k) if its DTW beats the k-th.
  void Verify(uint64_t word, uint32_t other, std::vector<WordNeighbour>* best) const {
    const double threshold =
        best->size() < options_.k ? std::numeric_limits<double>::infinity() : best->back().distance;
    const double dtw = distance_.Dtw(prepared_[word], prepared_[other], threshold);
    if (!(dtw <= threshold)) return;
    const WordNeighbour found{other, static_cast<float>(dtw)};
    auto position = std::upper_bound(
        best->begin(), best->end(), found, [](const WordNeighbour& a, const WordNeighbour& b) {
          return a.distance < b.distance || (a.distance == b.distance && a.word < b.word);
        });
    best->insert(position, found);
    if (best->size() > options_.k) best->pop_back();
  }

  const WordPool& pool_;
  const DtwNeighbourOptions& options_;
  const RowMatrixXf& descriptors_;
  const RowMatrixXf& centroids_;
  const std::vector<std::vector<uint32_t>>& members_;
  const WordDistance& distance_;
  const std::vector<PreparedWord>& prepared_;
  const uint32_t lists_;
  const uint32_t probes_;
};

}  // namespace

Result<std::vector<std::vector<WordNeighbour>>> FindDtwNeighbours(
    const WordPool& pool, const DtwNeighbourOptions& options) {
  if (options.k == 0 || options.probes == 0) {
    return Status::InvalidArgument("dtw neighbours: k and probes must be at least 1");
  }
  if (pool.size() == 0) return Status::InvalidArgument("dtw neighbours: an empty pool");
  const uint64_t n = pool.size();
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  const RowMatrixXf descriptors = Descriptors(pool, arena);
  MOTIF_ASSIGN_OR_RETURN(RowMatrixXf centroids, FitLists(descriptors, ListCount(options, n),
                                                         options.seed, options.threads));
  const std::vector<std::vector<uint32_t>> members = InvertedLists(descriptors, centroids, arena);
  const WordDistance distance(pool.joint_weights(), pool.word_frames(), options.band_frames);
  const std::vector<PreparedWord> prepared = PrepareWords(pool, distance, arena);

  const DtwNeighbourSearch search(pool, options, descriptors, centroids, members, distance,
                                  prepared);
  std::vector<std::vector<WordNeighbour>> neighbours(n);
  std::atomic<uint64_t> done{0};
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, n, 64),
                      [&](const tbb::blocked_range<uint64_t>& range) {
                        DtwNeighbourSearch::Scratch scratch;
                        for (uint64_t word = range.begin(); word != range.end(); ++word) {
                          search.Find(word, &scratch, &neighbours[word]);
                          if (options.progress) options.progress(++done, n);
                        }
                      });
  });
  return neighbours;
}

}  // namespace motif
