#include "engine/trellis/trellis_builder.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>

#include "common/byte_coding.h"
#include "common/count_text.h"
#include "common/seconds_since.h"
#include "engine/distance/epsilon_estimator.h"
#include "engine/distance/exact_search.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/lsh_search.h"
#include "engine/lsh/lsh_tuning.h"
#include "engine/trellis/block_write_queue.h"
#include "engine/trellis/distributed_columns.h"
#include "engine/trellis/search_cache.h"
#include "engine/trellis/trellis_search.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {
namespace {

// Whether a finished trellis at `path` has these parameters; if so, its size into *report.
bool ReadReusable(const std::string& path, const TrellisParams& params, TrellisReport* report) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return false;
  Result<std::unique_ptr<TrellisFileReader>> existing = TrellisFileReader::Open(path);
  if (!existing.ok() || !((*existing)->params() == params)) return false;
  report->columns = (*existing)->column_count();
  report->neighbours = (*existing)->neighbour_count();
  report->mean_k = report->columns ? static_cast<double>(report->neighbours) / report->columns : 0;
  return true;
}

// The parameters as one line, for the ranks of a distributed run to check that they agree.
std::string ParamsDigest(const TrellisParams& params) {
  std::ostringstream out;
  out << params.frame_count << ' ' << params.archive_identity << ' ' << std::hexfloat << params.eps
      << ' ' << params.k_max << ' ' << params.exclusion_frames << ' ' << params.search_mode << ' '
      << params.seed << ' ' << params.weights_hash << ' ' << params.search_params;
  return out.str();
}

// What rank 0 tells the others before the search: whether the finished trellis is reused and
// where the build starts.
struct BuildPlan {
  bool reused = false;
  uint64_t first_column = 0;
};

// Collective: rank 0's plan to every rank, with its parameters, which must be every rank's (an
// archive that differs between nodes, or other options, would give other columns).
Status AgreeOnPlan(RankGroup* ranks, const TrellisParams& params, BuildPlan* plan) {
  std::string message;
  if (ranks->rank() == 0) {
    message = std::to_string(plan->reused ? 1 : 0) + ' ' + std::to_string(plan->first_column) +
              ' ' + ParamsDigest(params);
  }
  MOTIF_RETURN_IF_ERROR(ranks->Broadcast(&message));
  std::istringstream in(message);
  int reused = 0;
  in >> reused >> plan->first_column;
  in.get();
  std::string digest;
  std::getline(in, digest, '\0');
  if (digest != ParamsDigest(params)) {
    return Status::InvalidArgument(
        "rank " + std::to_string(ranks->rank()) +
        ": its trellis parameters differ from rank 0's (another archive on this node, or other "
        "options?): " +
        ParamsDigest(params) + " against " + digest);
  }
  plan->reused = reused != 0;
  return Status::Ok();
}

// A distributed run's columns (distributed_columns.h); rank 0 gets the counters and the bytes.
Status WriteColumnsAcrossRanks(const NeighbourSearch& search, const TrellisOptions& options,
                               const TrellisParams& params, TrellisFileWriter* writer,
                               TrellisReport* report, SearchStats* stats) {
  DistributedColumnsPlan plan;
  plan.first_column = report->resumed_from_column;
  plan.frame_count = params.frame_count;
  plan.block_columns = options.block_columns;
  plan.eps = params.eps;
  plan.zstd_level = TrellisFileWriterOptions().zstd_level;
  MOTIF_ASSIGN_OR_RETURN(DistributedColumnsReport columns,
                         SearchColumnsAcrossRanks(search, options.ranks, plan, writer,
                                                  [&](uint64_t done, uint64_t total) {
                                                    if (options.progress)
                                                      options.progress("trellis", done, total);
                                                  }));
  *stats = columns.stats;
  report->receive_wait_seconds = columns.receive_wait_seconds;
  report->write_wait_seconds = columns.write_wait_seconds;
  report->write_seconds = columns.write_seconds;
  MOTIF_ASSIGN_OR_RETURN(report->rank_bytes_sent,
                         options.ranks->GatherToRoot(options.ranks->bytes_sent()));
  // In microseconds, as integers.
  MOTIF_ASSIGN_OR_RETURN(std::vector<uint64_t> micros,
                         options.ranks->GatherToRoot(
                             static_cast<uint64_t>(std::llround(columns.search_seconds * 1e6))));
  for (uint64_t micro : micros) report->rank_search_seconds.push_back(micro / 1e6);
  return Status::Ok();
}

// One process's columns: while block b is compressed and written (fsynced) on a writer thread,
// block b + 1 is searched by all the search threads. Blocks are written in order, so the file
// is the same as with a serial loop.
Status WriteColumnsHere(const NeighbourSearch& search, const TrellisOptions& options,
                        const std::string& trellis_path, TrellisFileWriter* writer,
                        TrellisReport* report, SearchStats* stats) {
  auto progress = [&](uint64_t done, uint64_t total) {
    if (options.progress) options.progress("trellis", done, total);
  };
  const uint64_t frame_count = report->params.frame_count;
  const uint64_t block_columns = writer->block_columns();
  progress(writer->next_column(), frame_count);
  BlockWriteQueue queue(writer);
  uint64_t pending_end = 0;  // the last column + 1 of the write in flight
  // Waits for the write in flight; then reports progress and applies stop_after_blocks.
  auto finish_pending_write = [&]() -> Status {
    if (pending_end == 0) return Status::Ok();
    MOTIF_RETURN_IF_ERROR(queue.Wait(&report->write_wait_seconds));
    report->write_seconds = queue.write_seconds();
    progress(pending_end, frame_count);
    if (options.stop_after_blocks > 0 &&
        pending_end - report->resumed_from_column >= options.stop_after_blocks * block_columns) {
      return Status::IOError(trellis_path + ": build stopped after " +
                             std::to_string(options.stop_after_blocks) + " blocks (as asked)");
    }
    return Status::Ok();
  };
  for (uint64_t first = writer->next_column(); first < frame_count; first += block_columns) {
    const uint64_t count = std::min<uint64_t>(block_columns, frame_count - first);
    std::vector<std::vector<Neighbour>> columns(count);
    MOTIF_RETURN_IF_ERROR(search.SearchColumns(first, count, &columns, stats));
    // A search may leave a column's capacity at everything it found within eps (the exact
    // search: thousands of entries at large N) although it keeps at most k_max: give it back
    // before the block waits for the writer, so two blocks in flight cost no more than one.
    for (std::vector<Neighbour>& column : columns) column.shrink_to_fit();
    MOTIF_RETURN_IF_ERROR(finish_pending_write());
    pending_end = first + count;
    queue.StartColumns(std::move(columns));
  }
  return finish_pending_write();
}

// InvalidOption for options no build can run with.
Status CheckTrellisOptions(const TrellisOptions& options) {
  if (options.k_max == 0) return Status::InvalidOption("kmax", "must be at least 1");
  if (options.eps < 0 || !std::isfinite(options.eps)) {
    return Status::InvalidOption("eps", "must be a positive number or auto");
  }
  if (options.exact && options.search == TrellisSearchMode::kLsh) {
    return Status::InvalidOption("search", "lsh contradicts the exact search asked for");
  }
  return Status::Ok();
}

// The search: as asked, or by the archive's size (the exact search is faster on small ones).
TrellisSearchMode ChooseSearchMode(const TrellisOptions& options, uint64_t frame_count,
                                   const std::function<void(const std::string&)>& note) {
  TrellisSearchMode mode = options.exact ? TrellisSearchMode::kExact : options.search;
  if (mode != TrellisSearchMode::kAuto) return mode;
  mode = frame_count < options.auto_exact_max_frames ? TrellisSearchMode::kExact
                                                     : TrellisSearchMode::kLsh;
  note(std::string("search: ") + TrellisSearchModeName(mode) + " (auto: " +
       CountOf(frame_count, "frame") + ", exact below " +
       WithCommas(options.auto_exact_max_frames) + ")");
  return mode;
}

// The radius: explicit, or estimated by the rule; into params (eps, mu, sigma) and the report.
Status ChooseRadius(const PoseFeatures& features, const NeighbourRules& rules,
                    const TrellisOptions& options, TrellisParams* params, TrellisReport* report,
                    const std::function<void(const std::string&)>& note) {
  const auto start = std::chrono::steady_clock::now();
  EpsilonOptions eps_options;
  eps_options.rule = options.eps_rule;
  eps_options.joint_angle_degrees = options.eps_joint_angle_degrees;
  eps_options.sample_pairs = options.eps_sample_pairs;
  eps_options.seed = options.seed;
  eps_options.threads = options.threads > 0 ? static_cast<uint32_t>(options.threads) : 0;
  if (options.eps > 0) eps_options.explicit_eps = options.eps;
  EpsilonEstimator estimator(features, rules, eps_options);
  MOTIF_ASSIGN_OR_RETURN(EpsilonEstimate estimate, estimator.Estimate());
  params->eps = estimate.eps;
  if (!estimate.explicit_eps) {
    params->mu = static_cast<float>(estimate.mu);
    params->sigma = static_cast<float>(estimate.sigma);
  }
  report->eps_how = estimate.how;
  report->paper_eps = estimate.paper_eps;
  if (!estimate.note.empty()) note(estimate.note);
  report->eps_seconds = SecondsSince(start);
  return Status::Ok();
}

// The features, the LSH tables (none for the exact search) of a finished build, for the next
// incremental update. Best effort: a cache.
void SaveSearchCache(const TrellisOptions& options, const FrameFileReader& archive,
                     const PoseFeatures& features, const TrellisSearch& search,
                     const TrellisParams& params,
                     const std::function<void(const std::string&)>& note) {
  const SearchCacheKey key{archive.summary().identity, params.weights_hash,
                           search.lsh ? DescribeLshOptions(search.lsh->options()) : ""};
  const Status saved =
      WriteSearchCache(options.search_cache_path, key, features,
                       search.lsh ? &search.lsh->index() : nullptr, 0, {}, options.file_system);
  if (!saved.ok()) note("search cache not saved (the next run rebuilds it): " + saved.message());
}

// Rank 0's writer (opened first in a distributed run, to tell the others where to start), and
// whether the finished trellis is reused; every rank learns both.
Status OpenWriterAndAgree(const TrellisOptions& options, const std::string& trellis_path,
                          const TrellisParams& params, TrellisReport* report,
                          std::unique_ptr<TrellisFileWriter>* writer) {
  const bool root = options.ranks == nullptr || options.ranks->rank() == 0;
  if (root) report->reused = ReadReusable(trellis_path, params, report);
  TrellisFileWriterOptions writer_options;
  writer_options.block_columns = options.block_columns;
  if (root && !report->reused) {
    MOTIF_ASSIGN_OR_RETURN(*writer,
                           TrellisFileWriter::OpenOrResume(trellis_path, params, writer_options));
    report->resumed_from_column = (*writer)->next_column();
  }
  if (options.ranks == nullptr) return Status::Ok();
  BuildPlan plan{report->reused, report->resumed_from_column};
  MOTIF_RETURN_IF_ERROR(AgreeOnPlan(options.ranks, params, &plan));
  report->reused = plan.reused;
  report->resumed_from_column = plan.first_column;
  return Status::Ok();
}

// The columns, searched and written block by block; then the counters and the file's size.
Status WriteAllColumns(const TrellisSearch& search, const TrellisOptions& options,
                       const std::string& trellis_path, TrellisFileWriter* writer,
                       TrellisReport* report) {
  const auto start = std::chrono::steady_clock::now();
  SearchStats stats;
  if (options.ranks != nullptr) {
    MOTIF_RETURN_IF_ERROR(
        WriteColumnsAcrossRanks(*search.search, options, report->params, writer, report, &stats));
    if (options.ranks->rank() != 0) return Status::Ok();
  } else {
    MOTIF_RETURN_IF_ERROR(
        WriteColumnsHere(*search.search, options, trellis_path, writer, report, &stats));
  }
  MOTIF_RETURN_IF_ERROR(writer->Finish());
  report->search_seconds = SecondsSince(start);
  report->distance_evaluations = stats.distance_evaluations;
  report->capped_columns = stats.capped_columns;
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> finished,
                         TrellisFileReader::Open(trellis_path));
  report->columns = finished->column_count();
  report->neighbours = finished->neighbour_count();
  report->mean_k = report->columns ? static_cast<double>(report->neighbours) / report->columns : 0;
  return Status::Ok();
}

}  // namespace

const char* TrellisSearchModeName(TrellisSearchMode mode) {
  switch (mode) {
    case TrellisSearchMode::kAuto:
      return "auto";
    case TrellisSearchMode::kLsh:
      return "lsh";
    case TrellisSearchMode::kExact:
      return "exact";
  }
  return "?";
}

Result<TrellisSearchMode> ParseTrellisSearchMode(const std::string& name) {
  for (TrellisSearchMode mode :
       {TrellisSearchMode::kAuto, TrellisSearchMode::kLsh, TrellisSearchMode::kExact}) {
    if (name == TrellisSearchModeName(mode)) return mode;
  }
  return Status::InvalidOption("search", "must be auto, lsh or exact, not '" + name + "'");
}

uint64_t WeightsHash(const std::vector<float>& weights) {
  return Checksum64(weights.data(), weights.size() * sizeof(float));
}

bool IsTrellisOfArchive(const std::string& path, const FrameFileReader& archive) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return false;
  Result<std::unique_ptr<TrellisFileReader>> trellis = TrellisFileReader::Open(path);
  return trellis.ok() && (*trellis)->params().archive_identity == archive.summary().identity &&
         (*trellis)->params().frame_count == archive.frame_count();
}

std::string DefaultTrellisPath(const std::string& archive_path) {
  std::filesystem::path path(archive_path);
  if (path.extension() == ".mfs") path.replace_extension("");
  return path.string() + ".mtr";
}

Result<TrellisReport> BuildTrellis(const FrameFileReader& reader, const std::string& trellis_path,
                                   const TrellisOptions& options) {
  auto note = [&](const std::string& message) {
    if (options.note) options.note(message);
  };
  auto progress = [&](const std::string& stage, uint64_t done, uint64_t total) {
    if (options.progress) options.progress(stage, done, total);
  };
  MOTIF_RETURN_IF_ERROR(CheckTrellisOptions(options));
  if (reader.frame_count() >= (uint64_t{1} << 32)) {
    return Status::NotSupported(reader.path() + ": more than 2^32 frames");
  }
  MOTIF_ASSIGN_OR_RETURN(std::vector<float> weights,
                         LoadDistanceWeights(reader.skeleton(), options.weights_path));
  TrellisReport report;
  report.trellis_path = trellis_path;
  report.search = ChooseSearchMode(options, reader.frame_count(), note);
  const bool exact = report.search == TrellisSearchMode::kExact;
  auto start = std::chrono::steady_clock::now();
  progress("features", 0, reader.frame_count());
  MOTIF_ASSIGN_OR_RETURN(PoseFeatures features, PoseFeatures::FromArchive(
                                                    reader, weights,
                                                    [&](uint64_t done, uint64_t total) {
                                                      progress("features", done, total);
                                                    },
                                                    options.ranks));
  report.features_seconds = SecondsSince(start);
  report.feature_bytes = features.memory_bytes();

  const uint32_t exclusion = options.exclusion_frames > 0
                                 ? options.exclusion_frames
                                 : static_cast<uint32_t>(std::lround(
                                       motifmine::defaults::kMinLengthSeconds * reader.fps() / 2));
  NeighbourRules rules = TrellisRules(features, 0, options.k_max, exclusion);
  TrellisParams params;
  params.frame_count = reader.frame_count();
  params.archive_identity = reader.summary().identity;
  params.k_max = rules.k_max;
  params.exclusion_frames = rules.exclusion_frames;
  params.search_mode = exact ? 0 : 1;
  params.seed = options.seed;
  params.weights_hash = WeightsHash(weights);
  MOTIF_RETURN_IF_ERROR(ChooseRadius(features, rules, options, &params, &report, note));
  rules.eps = params.eps;

  // The file records the search as requested (the LSH bucket width "auto" included): the
  // width chosen from the data follows from the data and the seed.
  LshOptions lsh = options.lsh;
  lsh.seed = options.seed;
  lsh.threads = options.threads;
  params.search_params = exact ? "exact" : DescribeLshOptions(lsh);
  report.params = params;

  // A finished trellis with the same parameters over the same archive is the answer already
  // (rank 0 decides for every rank).
  std::unique_ptr<TrellisFileWriter> writer;
  MOTIF_RETURN_IF_ERROR(OpenWriterAndAgree(options, trellis_path, params, &report, &writer));
  if (report.reused) {
    if (!exact) report.lsh_resolved = ResolveLshOptions(features, rules, lsh);
    return report;
  }
  start = std::chrono::steady_clock::now();
  MOTIF_ASSIGN_OR_RETURN(TrellisSearch search, MakeTrellisSearch(features, rules, exact, lsh,
                                                                 options.threads, options.ranks));
  if (search.lsh != nullptr) {
    if (options.detail) options.detail("LSH index: " + search.lsh->DescribeParams());
    report.lsh_resolved = search.lsh->options();
  }
  report.index_seconds = SecondsSince(start);
  if (report.resumed_from_column > 0) {
    note("resuming the interrupted build at column " + std::to_string(report.resumed_from_column));
  }
  MOTIF_RETURN_IF_ERROR(WriteAllColumns(search, options, trellis_path, writer.get(), &report));
  const bool root = options.ranks == nullptr || options.ranks->rank() == 0;
  if (root && !options.search_cache_path.empty()) {
    SaveSearchCache(options, reader, features, search, params, note);
  }
  return report;
}

Result<TrellisReport> BuildTrellis(const std::string& archive_path, const std::string& trellis_path,
                                   const TrellisOptions& options) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileReader> reader,
                         FrameFileReader::OpenVersion(archive_path, options.archive_version));
  return BuildTrellis(*reader, trellis_path, options);
}

}  // namespace motif
