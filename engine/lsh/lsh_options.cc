#include "engine/lsh/lsh_options.h"

#include <cstdio>

namespace motif {

std::string DescribeLshOptions(const LshOptions& options) {
  char text[512];
  std::snprintf(
      text, sizeof(text),
      "lsh embedding=qqT tables=%u hashes=%u width=%.6g width_per_hash=%.4g probes=%u "
      "ranking=%s max_candidates=%u max_entries=%u max_bucket_scan=%u first_round_scan=%u "
      "extension_stages=%u "
      "sparse_radius_factor=%.3g chain_columns=%u chain_advance=%u "
      "chain_probe_every=%u chained_max_candidates=%u chain_sweeps=%u seed=%llu",
      options.tables, options.hashes_per_table, options.bucket_width, options.width_per_hash,
      options.probes_per_table, LshRankingName(options.ranking), options.max_candidates,
      options.max_entries, options.max_bucket_scan, options.first_round_scan,
      options.extension_stages, options.sparse_radius_factor, options.chain_columns,
      options.chain_advance, options.chain_probe_every, options.chained_max_candidates,
      options.chain_sweeps, static_cast<unsigned long long>(options.seed));
  return text;
}

const char* LshRankingName(LshRanking ranking) {
  return ranking == LshRanking::kPositionCode ? "code" : "sort";
}

bool ParseLshRanking(const std::string& text, LshRanking* ranking) {
  if (text == "sort") {
    *ranking = LshRanking::kSortValue;
  } else if (text == "code") {
    *ranking = LshRanking::kPositionCode;
  } else {
    return false;
  }
  return true;
}

}  // namespace motif
