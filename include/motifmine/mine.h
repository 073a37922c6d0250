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
#include "motifmine/status.h"

namespace motifmine {

// Every option of a run; a default-constructed MineOptions holds the defaults of `motifmine
// mine` (they are defined once, in the engine).
struct MineOptions {
  MOTIFMINE_API MineOptions();

  std::string out_dir;  // required: archive.mfs (imported takes), trellis, paths, motifs.json
  // The radius ε: > 0 explicit; 0 from the rule: "joint-angle" (eps_angle_degrees of rotation on
  // each weighted joint) or "paper" (μ − 2σ of sampled pair distances).
  double eps;
  std::string eps_rule;
  double eps_angle_degrees;
  uint32_t k_max;              // neighbours kept per frame
  uint32_t branch;             // branching factor B of the path grower
  double min_length_seconds;   // λ, used when min_length_frames is 0
  uint64_t min_length_frames;  // λ in frames; 0: from min_length_seconds
  uint32_t groups;             // number of motifs; 0: automatic
  uint64_t seed;               // every random choice
  int threads;                 // 0: all cores
  bool skip_bad;               // import: pass over takes that fail, and mine the others
  bool write_report;           // OUT/report.html
  uint64_t synth_frames;       // no inputs: frames of the built-in synthetic archive
  uint32_t synth_motifs;       // no inputs: motifs planted in it
  // Called as the run goes: the stage ("import", "synth", "trellis features", "trellis eps",
  // "trellis", "grow", "cluster"), how much of it is done, of how much.
  std::function<void(const std::string& stage, uint64_t done, uint64_t total)> progress;
};

struct Instance {
  std::string clip;
  uint64_t start = 0;  // first frame within the clip
  uint64_t end = 0;    // one past the last
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

}  // namespace motifmine
