#include "engine/trellis/trellis_search.h"

#include "engine/distance/exact_search.h"
#include "engine/lsh/hash_family.h"

namespace motif {

NeighbourRules TrellisRules(const PoseFeatures& features, float eps, uint32_t k_max,
                            uint32_t exclusion_frames) {
  NeighbourRules rules;
  rules.eps = eps;
  rules.k_max = k_max;
  rules.exclusion_frames = exclusion_frames;
  rules.clip_first_frames = features.clip_first_frames();
  return rules;
}

namespace {

// The saved tables extended by the frames after them, with the family they were hashed with.
Result<std::unique_ptr<LshSearch>> ExtendedLshSearch(const PoseFeatures& features,
                                                     const NeighbourRules& rules,
                                                     const LshOptions& lsh, int threads,
                                                     SavedLshTables* saved) {
  MOTIF_ASSIGN_OR_RETURN(
      LshIndex index,
      LshIndex::FromTables(saved->frame_count, std::move(saved->tables), saved->position_codes));
  const HashFamily family = HashFamily::Draw(features.weights(), lsh.tables, lsh.hashes_per_table,
                                             lsh.bucket_width, lsh.seed);
  MOTIF_RETURN_IF_ERROR(index.Extend(features, family, lsh.shard_frames, threads));
  return LshSearch::CreateWithIndex(features, rules, lsh, std::move(index));
}

}  // namespace

Result<TrellisSearch> MakeTrellisSearch(const PoseFeatures& features, const NeighbourRules& rules,
                                        bool exact, const LshOptions& lsh, int threads,
                                        RankGroup* ranks, SavedLshTables* saved) {
  TrellisSearch made;
  if (exact) {
    ExactSearchOptions options;
    options.threads = threads > 0 ? static_cast<uint32_t>(threads) : 0;
    made.search = std::make_unique<ExactSearch>(features, rules, options);
    return made;
  }
  std::unique_ptr<LshSearch> search;
  if (saved != nullptr) {
    MOTIF_ASSIGN_OR_RETURN(search, ExtendedLshSearch(features, rules, lsh, threads, saved));
  } else {
    MOTIF_ASSIGN_OR_RETURN(search, LshSearch::Create(features, rules, lsh, ranks));
  }
  made.lsh = search.get();
  made.search = std::move(search);
  return made;
}

}  // namespace motif
