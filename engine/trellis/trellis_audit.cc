#include "engine/trellis/trellis_audit.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <random>
#include <set>

#include "engine/distance/exact_search.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/lsh_search.h"
#include "engine/trellis/trellis_builder.h"
#include "engine/trellis/trellis_search.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {
namespace {

// `count` distinct columns of [0, frame_count), ascending; all of them if count >= frame_count.
std::vector<uint64_t> SampleColumns(uint64_t frame_count, uint64_t count, uint64_t seed) {
  std::vector<uint64_t> columns;
  if (count >= frame_count) {
    for (uint64_t column = 0; column < frame_count; ++column) columns.push_back(column);
    return columns;
  }
  std::mt19937_64 rng(seed);
  std::set<uint64_t> chosen;
  while (chosen.size() < count) chosen.insert(rng() % frame_count);
  return std::vector<uint64_t>(chosen.begin(), chosen.end());
}

// The archive, its trellis and the features the trellis was built from, checked to agree.
struct AuditInputs {
  std::unique_ptr<FrameFileReader> reader;
  std::unique_ptr<TrellisFileReader> trellis;
  PoseFeatures features;
  NeighbourRules rules;
};

Result<AuditInputs> OpenAuditInputs(const std::string& archive_path,
                                    const std::string& trellis_path, const AuditOptions& options) {
  AuditInputs inputs;
  MOTIF_ASSIGN_OR_RETURN(inputs.reader, FrameFileReader::Open(archive_path));
  MOTIF_ASSIGN_OR_RETURN(inputs.trellis, TrellisFileReader::Open(trellis_path));
  const TrellisParams& params = inputs.trellis->params();
  if (params.archive_identity != inputs.reader->summary().identity ||
      params.frame_count != inputs.reader->frame_count()) {
    return Status::InvalidArgument(trellis_path + " was built from another version of " +
                                   archive_path + ": rebuild it with motifmine trellis");
  }
  MOTIF_ASSIGN_OR_RETURN(std::vector<float> weights,
                         LoadDistanceWeights(inputs.reader->skeleton(), options.weights_path));
  if (WeightsHash(weights) != params.weights_hash) {
    return Status::InvalidOption("weights", "must be the joint weights " + trellis_path +
                                                " was built with, which are other ones");
  }
  MOTIF_ASSIGN_OR_RETURN(inputs.features, PoseFeatures::FromArchive(*inputs.reader, weights));
  inputs.rules = TrellisRules(inputs.features, params.eps, params.k_max, params.exclusion_frames);
  return inputs;
}

// The column recall over the sampled columns, as it is summed.
struct AuditTally {
  double column_recall_sum = 0;
  uint64_t columns_with_neighbours = 0;
  SearchStats exact_stats;
  double exact_seconds = 0;
};

// One sampled column: its exact eps-NN against the trellis's.
Status AuditColumn(const ExactSearch& exact, const TrellisFileReader& trellis, uint64_t column,
                   AuditTally* tally, AuditReport* report) {
  std::vector<std::vector<Neighbour>> exact_column(1);
  std::vector<std::vector<Neighbour>> stored;
  const auto start = std::chrono::steady_clock::now();
  const uint64_t capped_before = tally->exact_stats.capped_columns;
  MOTIF_RETURN_IF_ERROR(exact.SearchColumns(column, 1, &exact_column, &tally->exact_stats));
  const bool capped = tally->exact_stats.capped_columns > capped_before;
  tally->exact_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  MOTIF_RETURN_IF_ERROR(trellis.ReadColumns(column, 1, &stored));
  const std::vector<Neighbour>& truth = exact_column[0];
  const std::vector<Neighbour>& found = stored[0];
  report->trellis_entries += found.size();
  report->exact_entries += truth.size();
  uint64_t hits = 0;
  size_t found_idx = 0;
  for (const Neighbour& neighbour : truth) {  // both sorted by frame
    while (found_idx < found.size() && found[found_idx].frame < neighbour.frame) ++found_idx;
    if (found_idx < found.size() && found[found_idx].frame == neighbour.frame) ++hits;
  }
  report->found_entries += hits;
  if (capped) {
    report->capped_exact_entries += truth.size();
    report->capped_found_entries += hits;
    if (found.size() >= truth.size()) ++report->capped_columns_full;
  } else {
    report->uncapped_exact_entries += truth.size();
    report->uncapped_found_entries += hits;
  }
  if (!truth.empty()) {
    const double column_recall = static_cast<double>(hits) / truth.size();
    tally->column_recall_sum += column_recall;
    report->min_column_recall = std::min(report->min_column_recall, column_recall);
    ++tally->columns_with_neighbours;
  }
  return Status::Ok();
}

// The LSH work: a chained column is computed with its whole chain, so the LSH search is rerun
// on the whole chains of up to kLshTimedChains sampled columns (evenly spread over the sample),
// and its evaluations and time are per column of those chains.
Status TimeLshChains(const LshSearch& lsh, const std::vector<uint64_t>& sample,
                     uint64_t frame_count, AuditReport* report) {
  constexpr uint64_t kLshTimedChains = 16;
  const uint64_t chain = std::max<uint64_t>(1, lsh.options().chain_columns);
  std::set<uint64_t> chains;
  const uint64_t picks = std::min<uint64_t>(kLshTimedChains, sample.size());
  for (uint64_t idx = 0; idx < picks; ++idx) {
    chains.insert(sample[idx * sample.size() / picks] / chain);
  }
  SearchStats lsh_stats;
  double lsh_seconds = 0;
  std::vector<std::vector<Neighbour>> lsh_columns;
  for (uint64_t chain_idx : chains) {
    const uint64_t first = chain_idx * chain;
    const uint64_t count = std::min(chain, frame_count - first);
    const auto start = std::chrono::steady_clock::now();
    MOTIF_RETURN_IF_ERROR(lsh.SearchColumns(first, count, &lsh_columns, &lsh_stats));
    lsh_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  if (lsh_stats.columns > 0) {
    const double timed = static_cast<double>(lsh_stats.columns);
    report->lsh_timed_columns = lsh_stats.columns;
    report->lsh_evaluations_per_query = lsh_stats.distance_evaluations / timed;
    report->lsh_seconds_per_query = lsh_seconds / timed;
  }
  return Status::Ok();
}

void FinishAudit(const AuditTally& tally, uint64_t sampled_columns, AuditReport* report) {
  report->capped_exact_columns = tally.exact_stats.capped_columns;
  report->recall = report->exact_entries
                       ? static_cast<double>(report->found_entries) / report->exact_entries
                       : 1.0;
  report->mean_column_recall =
      tally.columns_with_neighbours ? tally.column_recall_sum / tally.columns_with_neighbours : 1.0;
  const double sampled = std::max<double>(1.0, static_cast<double>(sampled_columns));
  report->exact_evaluations_per_query = tally.exact_stats.distance_evaluations / sampled;
  report->exact_seconds_per_query = tally.exact_seconds / sampled;
}

}  // namespace

Result<AuditReport> AuditTrellis(const std::string& archive_path, const std::string& trellis_path,
                                 const AuditOptions& options) {
  MOTIF_ASSIGN_OR_RETURN(AuditInputs inputs, OpenAuditInputs(archive_path, trellis_path, options));
  const TrellisParams& params = inputs.trellis->params();
  AuditReport report;
  report.search_params = params.search_params;
  const std::vector<uint64_t> sample =
      SampleColumns(params.frame_count, options.sample_columns, options.seed);
  report.sampled_columns = sample.size();
  ExactSearchOptions exact_options;
  exact_options.threads = options.threads > 0 ? static_cast<uint32_t>(options.threads) : 0;
  const ExactSearch exact(inputs.features, inputs.rules, exact_options);
  AuditTally tally;
  for (size_t sample_idx = 0; sample_idx < sample.size(); ++sample_idx) {
    MOTIF_RETURN_IF_ERROR(AuditColumn(exact, *inputs.trellis, sample[sample_idx], &tally, &report));
    if (options.progress) options.progress(sample_idx + 1, sample.size());
  }
  FinishAudit(tally, sample.size(), &report);
  if (params.search_mode == 1) {
    LshOptions lsh_options = options.lsh;
    lsh_options.seed = params.seed;
    lsh_options.threads = options.threads;
    if (DescribeLshOptions(lsh_options) == params.search_params) {
      MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<LshSearch> lsh,
                             LshSearch::Create(inputs.features, inputs.rules, lsh_options));
      MOTIF_RETURN_IF_ERROR(TimeLshChains(*lsh, sample, params.frame_count, &report));
    }
  }
  return report;
}

}  // namespace motif
