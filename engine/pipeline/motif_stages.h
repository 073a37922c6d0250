// The stages after the trellis, shared by `mine` (MinePipeline) and `reindex` (which builds or
// updates its trellis its own way, incrementally): the paths grown through the trellis, then
// their clustering into motifs.json, each reused when its inputs and parameters did not change.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "common/status.h"
#include "engine/cluster/cluster_stage.h"
#include "engine/cluster/motif_clusterer.h"
#include "engine/grow/paths_builder.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

struct MotifStagesInput {
  std::string archive_path;                  // as motifs.json records it
  const FrameFileReader* archive = nullptr;  // the version the trellis was built from
  std::string trellis_path;
  std::string paths_path;
  std::string motifs_path;
  std::string state_path;  // the clustering's reuse key (mine_state.json, cluster_state.json)
  PathsOptions paths;      // archive_version is set from `archive`
  ClusterOptions cluster;
  // (stage, done, total, unit): "grow" in columns, then "cluster" in columns.
  std::function<void(const std::string&, uint64_t, uint64_t, const std::string&)> progress;
};

struct MotifStagesResult {
  PathsReport paths;
  ClusterStageResult clustered;
  double grow_seconds = 0;
  double cluster_seconds = 0;
};

// Grows (or reuses) the paths, then clusters (or reuses) the motifs. The stages' errors, naming
// their files.
Result<MotifStagesResult> RunMotifStages(const MotifStagesInput& input);

}  // namespace motif
