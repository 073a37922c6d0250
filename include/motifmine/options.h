// motifmine::MineOptions: every option of a mining run, the one options type of the library, the
// tool and the engine, and the option table that names, types, bounds and explains each of them
// (docs/guide.md, "Options"). A default-constructed MineOptions holds the defaults of
// `motifmine mine` (defaults.h). The tool's flags (`--kmax`), the Python keywords (`kmax`) and
// the fields of a reindex manifest (`params.kmax`) are the table's names; SetMineOption sets an
// option by that name from text, as the tool does. Part of the public API; no third-party type.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "motifmine/defaults.h"
#include "motifmine/export.h"
#include "motifmine/status.h"

namespace motifmine {

struct MineOptions {
  std::string out_dir;  // required: archive.mfs (imported takes), trellis, paths, motifs.json

  // The trellis. The radius ε: > 0 explicit; 0 from the rule: "joint-angle" (eps_angle_degrees
  // of rotation on each weighted joint) or "paper" (μ − 2σ of sampled pair distances).
  double eps = defaults::kEps;
  std::string eps_rule = defaults::kEpsRule;
  double eps_angle_degrees = defaults::kEpsAngleDegrees;
  uint32_t k_max = defaults::kKMax;                        // neighbours kept per frame
  uint32_t exclusion_frames = defaults::kExclusionFrames;  // 0: half the minimum length
  std::string search = defaults::kSearch;                  // "auto", "lsh" or "exact"
  std::string weights_path;  // per-joint weights ("joint weight" lines); empty: the defaults
  // The LSH search (docs/design/lsh.md); hashes and width 0: chosen from the archive.
  uint32_t lsh_tables = defaults::kLshTables;
  uint32_t lsh_hashes = defaults::kLshHashes;
  double lsh_width = defaults::kLshWidth;
  double lsh_width_per_hash = defaults::kLshWidthPerHash;
  uint32_t lsh_probes = defaults::kLshProbes;
  uint32_t lsh_max_candidates = defaults::kLshMaxCandidates;
  std::string lsh_ranking = defaults::kLshRanking;  // "sort" or "code"
  uint32_t lsh_max_entries = defaults::kLshMaxEntries;
  uint32_t lsh_chain_columns = defaults::kLshChainColumns;
  uint32_t lsh_chained_max_candidates = defaults::kLshChainedMaxCandidates;
  uint32_t lsh_chain_probe_every = defaults::kLshChainProbeEvery;
  uint32_t lsh_chain_sweeps = defaults::kLshChainSweeps;

  // The grower.
  uint32_t branch = defaults::kBranch;                      // branching factor B
  double min_length_seconds = defaults::kMinLengthSeconds;  // λ, used when min_length_frames is 0
  uint64_t min_length_frames = 0;                           // λ in frames; 0: from the seconds
  bool all_branches = false;  // keep every long path of a tree, not only its longest

  // The clustering.
  uint32_t groups = defaults::kGroups;                  // number of motifs; 0: automatic
  std::string similarity = defaults::kSimilarity;       // "warped" or "shared"
  double max_ncut = defaults::kMaxNcut;                 // automatic groups: the cut's stopping Ncut
  double min_similarity = defaults::kMinSimilarity;     // "shared": the least weight of an edge
  double max_length_ratio = defaults::kMaxLengthRatio;  // 0 keeps every instance
  double pause_speed = defaults::kPauseSpeed;           // degrees per second; 0: no trimming
  double pause_seconds = defaults::kPauseSeconds;

  // The run.
  uint64_t seed = defaults::kSeed;   // every random choice
  int threads = defaults::kThreads;  // 0: all cores
  bool skip_bad = false;             // import: pass over takes that fail, and mine the others
  std::string descriptions_path;     // import: an index of take descriptions
  bool write_report = true;          // OUT/report.html
  uint32_t playback_mb = defaults::kPlaybackMegabytes;  // the report's player data
  uint64_t synth_frames = defaults::kSynthFrames;  // no inputs: frames of the synthetic archive
  uint32_t synth_motifs = defaults::kSynthMotifs;  // no inputs: motifs planted in it

  // Called as the run goes: the stage ("import", "synth", "trellis features", "trellis eps",
  // "trellis", "grow", "cluster"), how much of it is done, of how much.
  std::function<void(const std::string& stage, uint64_t done, uint64_t total)> progress;
};

// One row of the option table.
struct OptionInfo {
  std::string name;           // the flag without "--", the Python keyword with '-' as '_'
  std::string type;           // "count", "integer", "number", "choice", "text", "switch",
                              // "length" (frames, or seconds with "s"), "groups", "radius"
  std::string default_value;  // as the tool's help shows it
  double min = 0;             // numbers: the least and the greatest value accepted
  double max = 0;
  bool min_exclusive = false;        // the least value itself is refused
  std::vector<std::string> choices;  // "choice": the values accepted
  std::string field;                 // the MineOptions field it sets
  std::vector<std::string> aliases;  // other Python keywords for it (older names)
  std::string help;
};

// Every option, in the order the tool's help lists them.
MOTIFMINE_API std::vector<OptionInfo> MineOptionTable();

// Sets the option `name` (a table name or alias) from text as the tool reads it ("256", "0.5s",
// "auto"); InvalidArgument naming the option for an unknown name or a value outside its range.
MOTIFMINE_API Status SetMineOption(MineOptions* options, const std::string& name,
                                   const std::string& value);
// The option as text (its table name or alias), as SetMineOption reads it.
MOTIFMINE_API std::string GetMineOption(const MineOptions& options, const std::string& name);

}  // namespace motifmine
