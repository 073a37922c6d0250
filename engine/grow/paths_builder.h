// BuildPaths: `motifmine grow`'s path-growing stage (docs/design/algorithm.md step 3): opens the
// archive (for its clips and frame rate) and its matching trellis, checks that the trellis was
// built over this version of the archive, streams the trellis through the PathGrower and writes
// the candidates to a paths file (formats/paths_file/) atomically.
//
// Reusable: the paths file records the trellis's identity and the grow parameters; an existing
// valid file with equal ones is the answer already (the grower is deterministic) and is reused.
// A changed trellis or parameter, or a damaged file, grows the paths again.
// Thread-safety: one build per paths file at a time.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/grow/path_grower.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/paths_file/paths_file_writer.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "motifmine/defaults.h"

namespace motif {

struct PathsOptions {
  uint32_t branch = GrowOptions{}.branch;
  // lambda: min_length_frames if > 0, else min_length_seconds at the archive's frame rate
  // (rounded, at least 1 frame): 0.5 s is 60 frames at 120 fps, as in the paper.
  uint64_t min_length_frames = 0;
  double min_length_seconds = motifmine::defaults::kMinLengthSeconds;
  bool all_branches = false;         // GrowOptions::all_branches (--all-branches)
  FrameFileVersion archive_version;  // the archive's version to read; default: the newest
  // (done_columns, total): (0, N) first and (N, N) last, not called when the file is reused.
  std::function<void(uint64_t done, uint64_t total)> progress;
};

struct PathsReport {
  std::string paths_path;
  bool reused = false;  // an existing paths file had the same trellis and parameters
  PathsParams params;   // branch, min_length in frames, trellis and archive identity
  uint64_t candidates = 0;
  uint64_t trellis_entries = 0;
  GrowStats stats;          // of this run (zero when reused)
  double grow_seconds = 0;  // streaming the trellis and growing
  double write_seconds = 0;
};

// "<archive without .mfs>.mpa": where `motifmine grow` writes an archive's paths.
std::string DefaultPathsPath(const std::string& archive_path);

// lambda in frames for a length in seconds at `fps`: round(seconds * fps), at least 1.
uint64_t MinLengthFrames(double seconds, double fps);

// Grows (or reuses) the paths of `trellis` (the trellis of `archive`) into `paths_path`.
// IOError for the write; InvalidOption for parameters ("branch", "min-length"); InvalidArgument
// if the trellis was built over another archive or another version of it; Corruption from the
// trellis.
Result<PathsReport> BuildPaths(const FrameFileReader& archive, const TrellisFileReader& trellis,
                               const std::string& paths_path, const PathsOptions& options);
// The same with the files opened here (the archive at options.archive_version): NotFound /
// Corruption for them, naming them.
Result<PathsReport> BuildPaths(const std::string& archive_path, const std::string& trellis_path,
                               const std::string& paths_path, const PathsOptions& options);

// A grower fed the trellis's blocks as a trellis stage writes them (the incremental update),
// so that the paths need no second pass over the file. Blocks that do not continue from where
// it stands (an update resumed after its start) are ignored; the paths are then grown by
// BuildPaths from the file.
class StreamedPaths {
 public:
  // InvalidOption for the grow parameters, as BuildPaths.
  static Result<std::unique_ptr<StreamedPaths>> Create(const FrameFileReader& archive,
                                                       const PathsOptions& options);
  Status AddBlock(uint64_t first_column, const std::vector<std::vector<Neighbour>>& columns);
  // Writes the paths file when every column was added (a later BuildPaths with the same
  // parameters then reuses it); does nothing otherwise. IOError / ResourceExhausted.
  Status FinishIfComplete(const TrellisFileReader& trellis, const std::string& paths_path);

 private:
  StreamedPaths(std::unique_ptr<PathGrower> grower, GrowOptions grow, uint64_t frame_count,
                uint64_t archive_identity);
  std::unique_ptr<PathGrower> grower_;
  GrowOptions grow_;
  uint64_t frame_count_;
  uint64_t archive_identity_;
};

}  // namespace motif
