#include "engine/pipeline/motif_stages.h"

#include "common/seconds_since.h"

namespace motif {

Result<MotifStagesResult> RunMotifStages(const MotifStagesInput& input) {
  using Clock = std::chrono::steady_clock;
  MotifStagesResult result;
  const auto progress = [&](const std::string& stage, uint64_t done, uint64_t total) {
    if (input.progress) input.progress(stage, done, total, "columns");
  };

  PathsOptions paths = input.paths;
  paths.archive_version = input.archive->version();
  paths.progress = [&](uint64_t done, uint64_t total) { progress("grow", done, total); };
  Clock::time_point start = Clock::now();
  MOTIF_ASSIGN_OR_RETURN(
      result.paths, BuildPaths(input.archive_path, input.trellis_path, input.paths_path, paths));
  result.grow_seconds = SecondsSince(start);

  ClusterStageInput cluster_input;
  cluster_input.archive_path = input.archive_path;
  cluster_input.archive = input.archive;
  cluster_input.trellis_path = input.trellis_path;
  cluster_input.paths_path = input.paths_path;
  cluster_input.paths_params = result.paths.params;
  cluster_input.candidates = result.paths.candidates;
  cluster_input.motifs_path = input.motifs_path;
  cluster_input.state_path = input.state_path;
  ClusterOptions cluster = input.cluster;
  cluster.progress = [&](const std::string&, uint64_t done, uint64_t total) {
    progress("cluster", done, total);
  };
  start = Clock::now();
  MOTIF_ASSIGN_OR_RETURN(result.clustered, RunClusterStage(cluster_input, cluster));
  result.cluster_seconds = SecondsSince(start);
  return result;
}

}  // namespace motif
