// motifmine cluster ARCHIVE [...]: clusters the grown paths into motifs (instances merged, their
// similarity read back from the trellis, normalized cut) and writes DIR/motifs.json; with
// --truth, scores the motifs against a synthetic archive's planted ones.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "engine/cli/cli_common.h"
#include "engine/cluster/cluster_stage.h"
#include "engine/cluster/motif_clusterer.h"
#include "engine/cluster/motifs_json.h"
#include "engine/evaluation/planted_motif_score.h"
#include "engine/grow/paths_builder.h"
#include "engine/synth/truth_json_reader.h"
#include "engine/trellis/trellis_builder.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/paths_file/paths_file_reader.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

struct LoadedPaths {
  std::vector<PathCandidate> candidates;
  PathsParams params;
};

// The grower's candidates from the paths file, checked to belong to `trellis`.
Result<LoadedPaths> LoadPathCandidates(const std::string& paths_path,
                                       const TrellisFileReader& trellis) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<PathsFileReader> reader,
                         PathsFileReader::Open(paths_path));
  if (reader->params().trellis_identity != trellis.identity() ||
      reader->params().frame_count != trellis.column_count()) {
    return Status::InvalidArgument(paths_path + " was grown from another trellis than " +
                                   trellis.path() + " (run `motifmine grow` again)");
  }
  return LoadedPaths{reader->candidates(), reader->params()};
}

int PrintTruthScore(const std::string& truth_path, const MotifsDocument& document) {
  Result<TruthFile> truth = ReadTruthJson(truth_path);
  if (!truth.ok()) return ReportError("cluster", truth.status());
  const PlantedMotifScore score = ScoreMotifsDocument(document, truth->instances);
  std::printf("  truth        %s: %u planted motifs, %s instances\n", truth_path.c_str(),
              score.planted_motifs, WithCommas(score.planted).c_str());
  std::printf("  recall       %.4f  (%s of %s planted instances hit)\n", score.recall,
              WithCommas(score.planted_hit).c_str(), WithCommas(score.planted).c_str());
  std::printf("  precision    %.4f  (%s of %s found instances hit a planted one)\n",
              score.precision, WithCommas(score.found_hitting).c_str(),
              WithCommas(score.found).c_str());
  std::printf("  ARI          %.4f  (found vs planted motif of the hit instances)\n",
              score.adjusted_rand_index);
  return kExitOk;
}

}  // namespace

int RunCluster(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "cluster";
  spec.usage =
      "motifmine cluster ARCHIVE [--trellis PATH] [--paths PATH] [--groups G|auto] "
      "[--seed S] --out DIR [--truth FILE.truth.json]";
  spec.summary =
      "Clusters the paths grown by `motifmine grow` into motifs: keeps the longest path per\n"
      "tree, merges instances that overlap by 3/4, scores instance pairs by the similar frames\n"
      "they share in the trellis (plus the path links), and groups them by normalized cut\n"
      "(Shi & Malik), recursively until no cut is cheap (--groups auto) or into G groups.\n"
      "Writes DIR/motifs.json, motifs most important first. --truth scores them against the\n"
      "planted motifs of a synthetic archive (recall, precision, adjusted Rand index).";
  NormalizedCutOptions cut_defaults;
  SimilarityOptions similarity_defaults;
  spec.options.add_options()("trellis", po::value<std::string>()->default_value(""),
                             "default: ARCHIVE.mtr")(
      "paths", po::value<std::string>()->default_value(""), "default: ARCHIVE.mpa")(
      "groups", po::value<std::string>()->default_value("auto"),
      "number of motifs G, or auto (cut while a cut's Ncut is below --max-ncut)")(
      "seed", po::value<uint64_t>()->default_value(1), "seed of the sparse eigensolver")(
      "out", po::value<std::string>(), "output folder (created if missing): DIR/motifs.json")(
      "truth", po::value<std::string>()->default_value(""),
      "a synthetic archive's truth file: print recall, precision and ARI")(
      "threads", po::value<int>()->default_value(0), "threads (0: all cores)")(
      "similarity", po::value<std::string>()->default_value("warped"),
      "how instance pairs are weighted for the normalized cut: warped (the time-warped distance of "
      "their motions, each instance scaled by its nearest repetition) or shared (the similar "
      "frames they share, as in the paper)")(
      "max-ncut", po::value<double>()->default_value(cut_defaults.max_ncut),
      "auto: stop cutting a group when its best cut's Ncut (0..2) is not below this")(
      "min-similarity", po::value<double>()->default_value(similarity_defaults.min_similarity),
      "instance pairs sharing less than this fraction of the shorter get no edge")(
      "max-length-ratio", po::value<double>()->default_value(ClusterOptions{}.max_length_ratio),
      "drop an instance from its motif when its length is more than this factor from the "
      "motif's median (a fragment or a run-on; 0 keeps all)");
  AddPauseOptions(spec);
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  if (!vm.count("out")) {
    std::fprintf(stderr, "motifmine cluster: error: --out DIR is required\nusage: %s\n",
                 spec.usage.c_str());
    return kExitUsage;
  }
  const std::string archive = vm["archive"].as<std::string>();
  std::string trellis_path = vm["trellis"].as<std::string>();
  if (trellis_path.empty()) trellis_path = DefaultTrellisPath(archive);
  std::string paths_path = vm["paths"].as<std::string>();
  if (paths_path.empty()) paths_path = DefaultPathsPath(archive);
  const std::string out_dir = vm["out"].as<std::string>();

  ClusterOptions options;
  if (Status status = ParseGroups(vm["groups"].as<std::string>(), &options.cut.groups);
      !status.ok()) {
    return ReportError("cluster", status);
  }
  options.seed = vm["seed"].as<uint64_t>();
  options.threads = vm["threads"].as<int>();
  if (Status status = PauseOptionsFrom(vm, &options.pauses); !status.ok()) {
    return ReportError("cluster", status);
  }
  options.cut.max_ncut = vm["max-ncut"].as<double>();
  options.similarity.min_similarity = vm["min-similarity"].as<double>();
  options.max_length_ratio = vm["max-length-ratio"].as<double>();
  if (Status status = ParseSimilarity(vm["similarity"].as<std::string>(), &options.warped.enabled);
      !status.ok()) {
    return ReportError("cluster", status);
  }
  if (!(options.cut.max_ncut > 0) || !(options.similarity.min_similarity > 0) ||
      options.similarity.min_similarity > 1) {
    return ReportError("cluster", Status::InvalidArgument(
                                      "--max-ncut must be > 0 and --min-similarity in (0, 1]"));
  }
  if (!(options.max_length_ratio == 0 || options.max_length_ratio >= 1) ||
      !std::isfinite(options.max_length_ratio)) {
    return ReportError("cluster",
                       Status::InvalidArgument("--max-length-ratio must be 0 (keep all) or >= 1"));
  }

  Result<std::unique_ptr<FrameFileReader>> frames = FrameFileReader::Open(archive);
  if (!frames.ok()) return ReportError("cluster", frames.status());
  Result<std::unique_ptr<TrellisFileReader>> trellis = TrellisFileReader::Open(trellis_path);
  if (!trellis.ok()) return ReportError("cluster", trellis.status());
  if ((*trellis)->params().archive_identity != (*frames)->summary().identity ||
      (*trellis)->column_count() != (*frames)->frame_count()) {
    return ReportError(
        "cluster", Status::InvalidArgument(trellis_path + " was built over another archive than " +
                                           archive + " (or another version of it)"));
  }
  Result<LoadedPaths> paths = LoadPathCandidates(paths_path, **trellis);
  if (!paths.ok()) return ReportError("cluster", paths.status());

  ProgressReporter progress(ProgressModeFrom(vm));
  bool started = false;
  options.progress = [&](const std::string& stage, uint64_t done, uint64_t total) {
    if (!started) progress.BeginStage(stage, total, "columns");
    started = true;
    progress.Update(done);
  };
  options.instances.min_length = paths->params.min_length;
  options.archive = frames->get();
  Result<ClusterResult> result = ClusterMotifs(paths->candidates, **trellis, options);
  if (started) progress.EndStage();
  if (!result.ok()) return ReportError("cluster", result.status());

  MotifsJsonParams params;
  params.eps = (*trellis)->params().eps;
  params.kmax = (*trellis)->params().k_max;
  params.branch = paths->params.branch;
  params.min_length = paths->params.min_length;
  params.groups = options.cut.groups;
  params.seed = options.seed;
  params.similarity = options.warped.enabled ? "warped" : "shared";
  if (options.archive != nullptr) {  // trimmed only with the archive
    params.pause_speed = options.pauses.max_speed;
    params.pause_seconds = options.pauses.min_seconds;
  }
  Result<MotifsDocument> document =
      MakeMotifsDocument(*result, archive, (*frames)->frame_count(), (*frames)->clips(), params);
  if (!document.ok()) return ReportError("cluster", document.status());
  document->archive_version = ArchiveVersionOf(**frames);
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) {
    return ReportError("cluster",
                       Status::IOError("cannot create " + out_dir + ": " + error.message()));
  }
  const std::string out_path = (std::filesystem::path(out_dir) / "motifs.json").string();
  if (Status status = WriteMotifsJson(out_path, *document); !status.ok()) {
    return ReportError("cluster", status);
  }

  const ClusterReport& report = result->report;
  const InstanceSetStats& instances = report.instance_stats;
  const SimilarityStats& similarity = report.similarity_stats;
  std::printf("wrote %s\n", out_path.c_str());
  std::printf("  motifs       %s (groups %s; %s connected components)\n",
              WithCommas(result->motifs.size()).c_str(),
              params.groups ? std::to_string(params.groups).c_str() : "auto",
              WithCommas(report.cut_stats.components).c_str());
  std::printf(
      "  instances    %s in motifs (%s fragments dropped), of %s merged from "
      "%s segments of %s paths (%s candidates)\n",
      WithCommas(report.clustered_instances).c_str(), WithCommas(report.length_outliers).c_str(),
      WithCommas(instances.instances).c_str(), WithCommas(instances.raw_instances).c_str(),
      WithCommas(instances.kept_paths).c_str(), WithCommas(instances.candidates).c_str());
  std::printf(
      "  pauses       %s near the paths: %s segments trimmed to their movement, %s still "
      "(dropped)\n",
      WithCommas(report.pauses).c_str(), WithCommas(instances.trimmed_instances).c_str(),
      WithCommas(instances.still_instances).c_str());
  std::printf("  coverage     %s frames, %s of the archive\n",
              WithCommas(report.covered_frames).c_str(),
              Percent(report.covered_frames, (*frames)->frame_count()).c_str());
  std::printf(
      "  graph        %s edges (%s similar pairs, %s links), %s farther apart than %g scales "
      "dropped\n",
      WithCommas(similarity.edges).c_str(), WithCommas(similarity.similar_pairs).c_str(),
      WithCommas(similarity.linked_pairs).c_str(),
      WithCommas(report.warped_stats.dropped_edges).c_str(), options.warped.max_scales);
  std::printf(
      "  time         instances %.2fs, similarity %.2fs (%s blocks), warped distance %.2fs, cut "
      "%.2fs (%s eigenvectors)\n",
      report.instance_seconds, similarity.seconds, WithCommas(similarity.blocks_decoded).c_str(),
      report.warped_stats.seconds, report.cut_seconds,
      WithCommas(report.cut_stats.eigen_solves).c_str());
  for (size_t rank = 0; rank < std::min<size_t>(5, document->motifs.size()); ++rank) {
    const MotifsJsonMotif& motif = document->motifs[rank];
    const MotifsJsonInstance& first = motif.instances.front();
    std::printf("  motif %-6zu %zu instances, mean %.0f frames, e.g. %s [%llu, %llu)\n", rank,
                motif.instances.size(), result->motifs[rank].mean_length(), first.clip.c_str(),
                static_cast<unsigned long long>(first.start),
                static_cast<unsigned long long>(first.end));
  }
  const std::string truth = vm["truth"].as<std::string>();
  if (!truth.empty()) return PrintTruthScore(truth, *document);
  return kExitOk;
}

}  // namespace motif::cli
