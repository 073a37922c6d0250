// motifmine cluster ARCHIVE [...]: clusters the grown paths into motifs (instances merged, their
// similarity read back from the trellis, normalized cut) and writes DIR/motifs.json; with
// --truth, scores the motifs against a synthetic archive's planted ones.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "engine/cli/cli_common.h"
#include "engine/cli/table_options.h"
#include "engine/cluster/cluster_stage.h"
#include "engine/cluster/motif_clusterer.h"
#include "engine/cluster/motifs_json.h"
#include "engine/evaluation/planted_motif_score.h"
#include "engine/grow/paths_builder.h"
#include "engine/pipeline/stage_options.h"
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

CommandSpec ClusterCommandSpec() {
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
  spec.options.add_options()("trellis", po::value<std::string>()->default_value(""),
                             "default: ARCHIVE.mtr")(
      "paths", po::value<std::string>()->default_value(""), "default: ARCHIVE.mpa")(
      "out", po::value<std::string>(), "output folder (created if missing): DIR/motifs.json")(
      "truth", po::value<std::string>()->default_value(""),
      "a synthetic archive's truth file: print recall, precision and ARI");
  AddTableFlags(spec, kClusterFlags);
  AddTableFlags(spec, kRunFlags);
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  return spec;
}

// The archive, its trellis and the paths grown through it, each checked against the others.
struct ClusterInputs {
  std::string archive_path;
  std::string trellis_path;
  std::unique_ptr<FrameFileReader> archive;
  std::unique_ptr<TrellisFileReader> trellis;
  LoadedPaths paths;
};

Result<ClusterInputs> OpenClusterInputs(const po::variables_map& vm) {
  ClusterInputs inputs;
  inputs.archive_path = vm["archive"].as<std::string>();
  inputs.trellis_path = vm["trellis"].as<std::string>();
  if (inputs.trellis_path.empty()) inputs.trellis_path = DefaultTrellisPath(inputs.archive_path);
  std::string paths_path = vm["paths"].as<std::string>();
  if (paths_path.empty()) paths_path = DefaultPathsPath(inputs.archive_path);
  MOTIF_ASSIGN_OR_RETURN(inputs.archive, FrameFileReader::Open(inputs.archive_path));
  MOTIF_ASSIGN_OR_RETURN(inputs.trellis, TrellisFileReader::Open(inputs.trellis_path));
  if (inputs.trellis->params().archive_identity != inputs.archive->summary().identity ||
      inputs.trellis->column_count() != inputs.archive->frame_count()) {
    return Status::InvalidArgument(inputs.trellis_path + " was built over another archive than " +
                                   inputs.archive_path + " (or another version of it)");
  }
  MOTIF_ASSIGN_OR_RETURN(inputs.paths, LoadPathCandidates(paths_path, *inputs.trellis));
  return inputs;
}

// DIR/motifs.json; its path.
Result<std::string> WriteClusterDocument(const std::string& out_dir,
                                         const MotifsDocument& document) {
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) return Status::IOError("cannot create " + out_dir + ": " + error.message());
  const std::string out_path = (std::filesystem::path(out_dir) / "motifs.json").string();
  MOTIF_RETURN_IF_ERROR(WriteMotifsJson(out_path, document));
  return out_path;
}

void PrintClusterReport(const std::string& out_path, const ClusterResult& result,
                        const MotifsDocument& document, const ClusterOptions& options,
                        uint64_t frame_count) {
  const ClusterReport& report = result.report;
  const InstanceSetStats& instances = report.instance_stats;
  const SimilarityStats& similarity = report.similarity_stats;
  std::printf("wrote %s\n", out_path.c_str());
  std::printf("  motifs       %s (groups %s; %s connected components)\n",
              WithCommas(result.motifs.size()).c_str(),
              options.cut.groups ? std::to_string(options.cut.groups).c_str() : "auto",
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
              Percent(report.covered_frames, frame_count).c_str());
  std::printf(
      "  graph        %s edges (%s similar pairs, %s links), %s farther apart than %g scales "
      "dropped\n",
      WithCommas(similarity.edges).c_str(), WithCommas(similarity.similar_pairs).c_str(),
      WithCommas(similarity.linked_pairs).c_str(),
      WithCommas(report.warped_stats.dropped_edges).c_str(), options.warped.max_scales);
  std::printf(
      "  time         instances %.2fs, samples %.2fs, similarity %.2fs (%s blocks), warped distance "
      "%.2fs, cut %.2fs (%s eigenvectors), representatives %.2fs\n",
      report.instance_seconds, report.sample_seconds, similarity.seconds, WithCommas(similarity.blocks_decoded).c_str(),
      report.warped_stats.seconds, report.cut_seconds,
      WithCommas(report.cut_stats.eigen_solves).c_str(), report.representative_seconds);
  for (size_t rank = 0; rank < std::min<size_t>(5, document.motifs.size()); ++rank) {
    const MotifsJsonMotif& motif = document.motifs[rank];
    const MotifsJsonInstance& first = motif.instances.front();
    std::printf("  motif %-6zu %zu instances, mean %.0f frames, e.g. %s [%llu, %llu)\n", rank,
                motif.instances.size(), result.motifs[rank].mean_length(), first.clip.c_str(),
                static_cast<unsigned long long>(first.start),
                static_cast<unsigned long long>(first.end));
  }
}

}  // namespace

int RunCluster(const std::vector<std::string>& args) {
  CommandSpec spec = ClusterCommandSpec();
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  if (!vm.count("out")) {
    std::fprintf(stderr, "motifmine cluster: error: --out DIR is required\nusage: %s\n",
                 spec.usage.c_str());
    return kExitUsage;
  }
  const auto fail = [](const Status& status) { return ReportError("cluster", status); };
  motifmine::MineOptions mine;
  ReadTableFlags(spec, vm, &mine);
  Result<ClusterOptions> options = ClusterOptionsFor(mine);
  if (!options.ok()) return fail(options.status());
  Result<ClusterInputs> inputs = OpenClusterInputs(vm);
  if (!inputs.ok()) return fail(inputs.status());
  ProgressReporter progress(ProgressModeFrom(vm));
  bool started = false;
  options->progress = [&](const std::string& stage, uint64_t done, uint64_t total) {
    if (!started) progress.BeginStage(stage, total, "instance frames");  // instances overlap
    started = true;
    progress.Update(done);
  };
  options->instances.min_length = inputs->paths.params.min_length;
  options->archive = inputs->archive.get();
  Result<ClusterResult> result =
      ClusterMotifs(inputs->paths.candidates, *inputs->trellis, *options);
  if (started) progress.EndStage();
  if (!result.ok()) return fail(result.status());
  Result<MotifsDocument> document =
      ClusteredDocument(*result, inputs->archive_path, *inputs->archive, *inputs->trellis,
                        inputs->paths.params, *options);
  if (!document.ok()) return fail(document.status());
  Result<std::string> out_path = WriteClusterDocument(vm["out"].as<std::string>(), *document);
  if (!out_path.ok()) return fail(out_path.status());
  PrintClusterReport(*out_path, *result, *document, *options, inputs->archive->frame_count());
  const std::string truth = vm["truth"].as<std::string>();
  if (!truth.empty()) return PrintTruthScore(truth, *document);
  return kExitOk;
}

}  // namespace motif::cli
