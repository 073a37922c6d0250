// run.json: what a `mine` run measured and chose, beside its motifs.json, so that `motifmine
// report DIR` run again shows the same overview as the report `mine` wrote (the stage timings,
// the peak memory, the parameters, the planted-motif truth). docs/formats/run_json.md.
//
// The record names the motifs.json it describes by a checksum of its bytes; a reader uses the
// record only while that file is unchanged (a later `cluster` into the same folder makes it
// stale, and it is then ignored).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/status.h"

namespace motif {

struct RunStageTiming {
  std::string stage;
  double seconds = 0;
  bool reused = false;
};

struct RunRecord {
  uint64_t motifs_checksum = 0;  // Checksum64 of the motifs.json bytes described
  std::string parameters_text;   // the parameters as the report shows them
  std::vector<RunStageTiming> timings;
  double total_seconds = 0;
  uint64_t peak_memory_bytes = 0;
  std::string truth_path;  // a synthetic archive's truth file, relative to run.json's folder
  // --descriptions of the run, by clip name (the report shows them over the archive's).
  std::map<std::string, std::string> descriptions;
};

// Writes `record` to `path` atomically.
Status WriteRunRecord(const std::string& path, const RunRecord& record);

// The record at `path` if it describes the motifs.json at `motifs_path` as it is now: NotFound
// when there is none, InvalidArgument when it is malformed or describes another motifs.json.
// truth_path comes back usable from the current directory.
Result<RunRecord> ReadRunRecord(const std::string& path, const std::string& motifs_path);

}  // namespace motif
