#include "engine/trellis/trellis_strategy.h"

#include <filesystem>
#include <optional>

#include "engine/trellis/search_cache.h"
#include "engine/trellis/trellis_search.h"
#include "engine/trellis/trellis_update.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {
namespace {

// The new trellis's parameters: the previous one's over the grown archive, with the search as
// the recorded family names it. mu and sigma are 0: eps is given from now on, as `mine --eps`
// gives it.
TrellisParams UpdatedParams(const TrellisFileReader& previous, const FrameFileReader& archive,
                            bool exact, const LshOptions& lsh) {
  TrellisParams params = previous.params();
  params.frame_count = archive.frame_count();
  params.archive_identity = archive.summary().identity;
  params.mu = 0;
  params.sigma = 0;
  params.search_params = exact ? "exact" : DescribeLshOptions(lsh);
  return params;
}

bool FinishedWithParams(const std::string& path, const TrellisParams& params) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return false;
  Result<std::unique_ptr<TrellisFileReader>> done = TrellisFileReader::Open(path);
  return done.ok() && (*done)->params() == params;
}

// What an update starts from: the previous version's features, LSH tables and column
// thresholds when its cache describes them, else nothing (decoded and built again).
struct UpdateStart {
  PoseFeatures features;
  std::optional<SavedLshTables> tables;
  std::vector<float> thresholds;  // empty: computed from the old trellis
};

Result<UpdateStart> StartFromCache(const std::string& cache_path, const TrellisFileReader& previous,
                                   const FrameFileReader& archive,
                                   const std::vector<float>& weights, const SearchCacheKey& key,
                                   bool exact, const TrellisOptions& options) {
  auto progress = [&](uint64_t done, uint64_t total) {
    if (options.progress) options.progress("features", done, total);
  };
  progress(0, archive.frame_count());
  Result<SearchCache> cache = ReadSearchCache(cache_path);
  const bool cached = cache.ok() && cache->key == key &&
                      cache->features.frame_count() == previous.column_count() &&
                      (exact || cache->tables.size() == options.lsh.tables);
  UpdateStart start;
  if (!cached) {
    if (options.note) {
      options.note(
          "no search cache of the previous version" +
          (cache.ok() ? std::string(" for these parameters") : ": " + cache.status().message()) +
          "; decoding the whole archive");
    }
    MOTIF_ASSIGN_OR_RETURN(start.features, PoseFeatures::FromArchive(archive, weights, progress));
    return start;
  }
  MOTIF_ASSIGN_OR_RETURN(
      start.features,
      PoseFeatures::ExtendFromArchive(std::move(cache->features), archive, weights, progress));
  if (!exact) {
    start.tables =
        SavedLshTables{previous.column_count(), std::move(cache->tables), cache->position_codes};
  }
  if (cache->trellis_identity == previous.identity() &&
      cache->thresholds.size() == previous.column_count()) {
    start.thresholds = std::move(cache->thresholds);
  }
  return start;
}

void ReportUpdate(const TrellisUpdateReport& updated, TrellisReport* report,
                  const std::function<void(const std::string&)>& note) {
  report->updated = true;
  report->update = {updated.old_columns, updated.new_columns, updated.changed_columns,
                    updated.copied_blocks, updated.rewritten_blocks};
  report->distance_evaluations = updated.search_stats.distance_evaluations;
  report->capped_columns = updated.search_stats.capped_columns;
  if (note) {
    note("trellis update: " + std::to_string(updated.new_columns) + " new columns, " +
         std::to_string(updated.changed_columns) + " of " + std::to_string(updated.old_columns) +
         " old columns changed; " + std::to_string(updated.copied_blocks) + " blocks copied, " +
         std::to_string(updated.rewritten_blocks) + " rewritten");
  }
}

Status FillFromFile(const std::string& path, TrellisReport* report) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> written, TrellisFileReader::Open(path));
  report->params = written->params();
  report->columns = written->column_count();
  report->neighbours = written->neighbour_count();
  report->mean_k = report->columns ? static_cast<double>(report->neighbours) / report->columns : 0;
  return Status::Ok();
}

}  // namespace

Result<TrellisReport> FullTrellisBuild::Run(const TrellisStageInput& input) const {
  return BuildTrellis(*input.archive, input.trellis_path, input.options);
}

Result<TrellisReport> IncrementalTrellisUpdate::Run(const TrellisStageInput& input) const {
  const TrellisOptions& options = input.options;
  const FrameFileReader& archive = *input.archive;
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> previous,
                         TrellisFileReader::Open(previous_trellis_));
  const bool exact = options.exact || options.search == TrellisSearchMode::kExact;
  LshOptions lsh = options.lsh;
  lsh.seed = options.seed;
  lsh.threads = options.threads;
  const TrellisParams params = UpdatedParams(*previous, archive, exact, lsh);
  TrellisReport report;
  report.trellis_path = input.trellis_path;
  report.search = exact ? TrellisSearchMode::kExact : TrellisSearchMode::kLsh;
  report.eps_how = "the recorded eps";
  if (!exact) report.lsh_resolved = lsh;
  report.reused = FinishedWithParams(input.trellis_path, params);  // a killed run finished it
  if (!report.reused) {
    MOTIF_ASSIGN_OR_RETURN(std::vector<float> weights,
                           LoadDistanceWeights(archive.skeleton(), options.weights_path));
    const std::string family = exact ? "" : DescribeLshOptions(lsh);
    const SearchCacheKey previous_key{previous->params().archive_identity, WeightsHash(weights),
                                      family};
    MOTIF_ASSIGN_OR_RETURN(
        UpdateStart start,
        StartFromCache(previous_cache_, *previous, archive, weights, previous_key, exact, options));
    const NeighbourRules rules =
        TrellisRules(start.features, options.eps, options.k_max, options.exclusion_frames);
    MOTIF_ASSIGN_OR_RETURN(TrellisSearch search,
                           MakeTrellisSearch(start.features, rules, exact, lsh, options.threads,
                                             nullptr, start.tables ? &*start.tables : nullptr));
    std::vector<float> next_thresholds;
    TrellisUpdateOptions update;
    update.threads = options.threads;
    update.file_system = options.file_system;
    update.progress = options.progress;
    if (!start.thresholds.empty()) update.thresholds = &start.thresholds;
    update.next_thresholds = &next_thresholds;
    update.on_block = input.on_block;
    MOTIF_ASSIGN_OR_RETURN(TrellisUpdateReport updated,
                           UpdateTrellis(*previous, start.features, rules, *search.search, params,
                                         input.trellis_path, update));
    ReportUpdate(updated, &report, options.note);
    MOTIF_RETURN_IF_ERROR(FillFromFile(input.trellis_path, &report));
    if (!options.search_cache_path.empty()) {
      MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> written,
                             TrellisFileReader::Open(input.trellis_path));
      const Status saved = WriteSearchCache(
          options.search_cache_path, {archive.summary().identity, WeightsHash(weights), family},
          start.features, search.lsh ? &search.lsh->index() : nullptr, written->identity(),
          next_thresholds, options.file_system);
      if (!saved.ok() && options.note) {
        options.note("search cache not saved (the next run rebuilds it): " + saved.message());
      }
    }
    return report;
  }
  MOTIF_RETURN_IF_ERROR(FillFromFile(input.trellis_path, &report));
  return report;
}

}  // namespace motif
