#include "engine/cluster/cluster_stage.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "formats/paths_file/paths_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {
namespace {

constexpr int kClusterRulesVersion = 5;

// What determines a clustering: the paths (through the trellis identity, itself tied to its
// archive, and the grow parameters) and every option that changes the result.
std::string ClusterKey(const ClusterStageInput& input, const ClusterOptions& options) {
  std::ostringstream key;
  // rules: the version of the clustering's own rules (periodic paths, merging, near-copies,
  // ranking), so that a result of older rules is not reused.
  key << "rules=" << kClusterRulesVersion << " trellis=" << input.paths_params.trellis_identity
      << " branch=" << input.paths_params.branch << " min_length=" << input.paths_params.min_length
      << " all_branches=" << input.paths_params.all_branches << " candidates=" << input.candidates
      << " groups=" << options.cut.groups << " max_ncut=" << options.cut.max_ncut
      << " min_similarity=" << options.similarity.min_similarity
      << " max_length_ratio=" << options.max_length_ratio << " seed=" << options.seed
      << " warped=" << options.warped.enabled << " warped_neighbours=" << options.warped.neighbours
      << " warped_samples=" << options.warped.samples
      << " warped_fallback=" << options.warped.fallback_scale
      << " warped_floor=" << options.warped.floor_scale
      << " warped_max_scales=" << options.warped.max_scales
      << " pause_speed=" << options.pauses.max_speed
      << " pause_seconds=" << options.pauses.min_seconds;
  return key.str();
}

std::string StoredClusterKey(const std::string& state_path) {
  Result<std::string> text = ReadFileToString(state_path);
  if (!text.ok()) return "";
  const nlohmann::json state = nlohmann::json::parse(*text, nullptr, /*allow_exceptions=*/false);
  if (!state.is_object() || !state.contains("cluster_key") || !state["cluster_key"].is_string()) {
    return "";
  }
  return state["cluster_key"].get<std::string>();
}

// Whether every motif has its representative: a motifs.json written before them is clustered
// again rather than reused, so that a rerun's file has them too.
bool HasRepresentatives(const MotifsDocument& document) {
  return std::all_of(document.motifs.begin(), document.motifs.end(),
                     [](const MotifsJsonMotif& motif) { return motif.representative.has_value(); });
}

// Whether two paths from the current directory name the same file, as written.
bool SamePath(const std::string& a, const std::string& b) {
  return std::filesystem::absolute(a).lexically_normal() ==
         std::filesystem::absolute(b).lexically_normal();
}

}  // namespace

MotifsArchiveVersion ArchiveVersionOf(const FrameFileReader& archive) {
  const FrameFileSummary summary = archive.summary();
  return {summary.generation, summary.file_bytes, summary.identity};
}

Result<MotifsDocument> ClusteredDocument(const ClusterResult& clustered,
                                         const std::string& archive_path,
                                         const FrameFileReader& archive,
                                         const TrellisFileReader& trellis,
                                         const PathsParams& paths_params,
                                         const ClusterOptions& options) {
  MotifsJsonParams params;
  params.eps = trellis.params().eps;
  params.kmax = trellis.params().k_max;
  params.branch = paths_params.branch;
  params.min_length = paths_params.min_length;
  params.groups = options.cut.groups;
  params.seed = options.seed;
  params.similarity = options.warped.enabled ? "warped" : "shared";
  if (options.archive != nullptr) {  // trimmed only with the archive
    params.pause_speed = options.pauses.max_speed;
    params.pause_seconds = options.pauses.min_seconds;
  }
  MOTIF_ASSIGN_OR_RETURN(
      MotifsDocument document,
      MakeMotifsDocument(clustered, archive_path, archive.frame_count(), archive.clips(), params));
  document.archive_version = ArchiveVersionOf(archive);
  return document;
}

Result<ClusterStageResult> RunClusterStage(const ClusterStageInput& input,
                                           const ClusterOptions& options) {
  ClusterStageResult result;
  const std::string key = ClusterKey(input, options);
  const FrameFileReader& archive = *input.archive;
  if (StoredClusterKey(input.state_path) == key) {
    Result<MotifsDocument> stored = ReadMotifsJson(input.motifs_path);
    if (stored.ok() && stored->frames == archive.frame_count() &&
        stored->archive_version == ArchiveVersionOf(archive) &&
        SamePath(stored->archive, input.archive_path) && HasRepresentatives(*stored)) {
      result.document = std::move(stored.value());
      result.reused = true;
      return result;
    }
  }
  std::unique_ptr<TrellisFileReader> opened;
  if (input.trellis == nullptr) {
    MOTIF_ASSIGN_OR_RETURN(opened, TrellisFileReader::Open(input.trellis_path));
  }
  const TrellisFileReader* trellis = input.trellis ? input.trellis : opened.get();
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<PathsFileReader> paths,
                         PathsFileReader::Open(input.paths_path));
  ClusterOptions with_length = options;
  with_length.instances.min_length = input.paths_params.min_length;
  with_length.archive = input.archive;
  MOTIF_ASSIGN_OR_RETURN(ClusterResult clustered,
                         ClusterMotifs(paths->candidates(), *trellis, with_length));
  MOTIF_ASSIGN_OR_RETURN(result.document,
                         ClusteredDocument(clustered, input.archive_path, archive, *trellis,
                                           input.paths_params, with_length));
  result.report = clustered.report;
  MOTIF_RETURN_IF_ERROR(WriteMotifsJson(input.motifs_path, result.document));
  const nlohmann::json state = {{"version", 1}, {"cluster_key", key}};
  MOTIF_RETURN_IF_ERROR(AtomicWriteFile(input.state_path, state.dump(2) + "\n"));
  return result;
}

}  // namespace motif
