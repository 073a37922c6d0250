// RunClusterStage: the clustering stage of `motifmine mine` and `motifmine reindex`: the paths
// file's candidates clustered against their trellis (ClusterMotifs) into a motifs.json, or the
// motifs.json already there when a state file beside it says the same paths were clustered with
// the same options (the grower and the clustering are deterministic). motifs.json and the state
// file are each replaced atomically, motifs.json first: a state that names a clustering always
// describes the motifs.json beside it.
// Thread-safety: one stage per output folder at a time.
#pragma once

#include <string>

#include "common/status.h"
#include "engine/cluster/motif_clusterer.h"
#include "engine/cluster/motifs_json.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/paths_file/paths_file_writer.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {

struct ClusterStageInput {
  std::string archive_path;                  // as motifs.json records it
  const FrameFileReader* archive = nullptr;  // the version the trellis was built over
  std::string trellis_path;
  const TrellisFileReader* trellis = nullptr;  // that file, open already; null: opened here
  std::string paths_path;
  PathsParams paths_params;  // of the paths file (its trellis identity and grow options)
  uint64_t candidates = 0;   // in the paths file
  std::string motifs_path;   // written
  std::string state_path;    // written: {"version": 1, "cluster_key": ...}
};

struct ClusterStageResult {
  MotifsDocument document;
  bool reused = false;
  ClusterReport report;  // of this run (empty when reused)
};

// The archive version a reader has open, as motifs.json records it.
MotifsArchiveVersion ArchiveVersionOf(const FrameFileReader& archive);

// The motifs.json document of a clustering of `archive`'s paths (their parameters
// `paths_params`) through `trellis` with `options` (params.eps and kmax are the trellis's).
Result<MotifsDocument> ClusteredDocument(const ClusterResult& clustered,
                                         const std::string& archive_path,
                                         const FrameFileReader& archive,
                                         const TrellisFileReader& trellis,
                                         const PathsParams& paths_params,
                                         const ClusterOptions& options);

// Errors of the trellis and paths files (NotFound, Corruption), of the clustering, and of the
// writes (IOError, ResourceExhausted).
Result<ClusterStageResult> RunClusterStage(const ClusterStageInput& input,
                                           const ClusterOptions& options);

}  // namespace motif
