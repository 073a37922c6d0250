// motifmine::Mine: the whole mining job of `motifmine mine` as one call, with the same defaults
// and the same motifs (docs/guide.md, "motifmine mine"; docs/design/algorithm.md). Part of the
// public API (<motifmine/motifmine.h>); no third-party type.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "motifmine/archive.h"  // Clip
#include "motifmine/export.h"
#include "motifmine/options.h"  // MineOptions
#include "motifmine/status.h"

namespace motifmine {

struct Instance {
  std::string clip;
  uint64_t start = 0;  // first frame within the clip
  uint64_t end = 0;    // one past the last
  double fps = 0;      // the clip's frame rate (0 when unknown)
};

struct Motif {
  uint32_t id = 0;  // rank: 0 is the best
  std::vector<Instance> instances;
};

// The parameters the run chose or was given.
struct MineParameters {
  double eps = 0;
  std::string eps_how;  // how ε was chosen, in words
  uint32_t k_max = 0;
  uint32_t branch = 0;
  uint64_t min_length_frames = 0;
  uint64_t seed = 0;
};

struct StageTiming {
  std::string stage;
  double seconds = 0;
  bool reused = false;  // an earlier run's output was still valid
};

struct MineResult {
  std::vector<Motif> motifs;  // best first
  std::vector<Clip> clips;
  MineParameters parameters;
  std::vector<StageTiming> timings;
  std::string archive_path;
  std::string motifs_path;                 // OUT/motifs.json
  std::vector<std::string> skipped_takes;  // skip_bad: the takes passed over, with the reason
};

// Mines `inputs`: BVH / ASF+AMC takes and folders (imported into OUT/archive.mfs), one archive
// (.mfs), or none (a built-in synthetic archive with planted motifs). Fills *result on success.
// Fails with InvalidArgument for an impossible option, Busy when another run holds the folder,
// and the codes of docs/guide.md otherwise, the message naming the file.
MOTIFMINE_API Status Mine(const std::vector<std::string>& inputs, const MineOptions& options,
                          MineResult* result);

// The result of an earlier run read back from its output folder, without mining again: the
// motifs, clips and parameters of OUT/motifs.json, and the timings and how eps was chosen from
// OUT/run.json while it still describes that motifs.json (empty otherwise; skipped_takes are
// not recorded, so they are empty). archive_path is the archive motifs.json names, or
// OUT/archive.mfs when that one is gone and the folder holds one. NotFound naming the path for
// a missing folder or a folder without motifs.json; InvalidArgument / NotSupported for a
// malformed motifs.json.
MOTIFMINE_API Status LoadMineResult(const std::string& out_dir, MineResult* result);

}  // namespace motifmine
