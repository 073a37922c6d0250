#include "engine/grow/paths_builder.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <system_error>
#include <vector>

#include "common/seconds_since.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/paths_file/paths_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {

namespace {}  // namespace

std::string DefaultPathsPath(const std::string& archive_path) {
  std::filesystem::path path(archive_path);
  if (path.extension() == ".mfs") path.replace_extension("");
  return path.string() + ".mpa";
}

uint64_t MinLengthFrames(double seconds, double fps) {
  const double frames = std::round(seconds * fps);
  return frames < 1 ? 1 : static_cast<uint64_t>(frames);
}

Result<PathsReport> BuildPaths(const std::string& archive_path, const std::string& trellis_path,
                               const std::string& paths_path, const PathsOptions& options) {
  if (options.min_length_frames == 0 &&
      !(options.min_length_seconds > 0 && std::isfinite(options.min_length_seconds))) {
    return Status::InvalidArgument("the minimum path length must be positive");
  }
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileReader> archive,
                         FrameFileReader::OpenVersion(archive_path, options.archive_version));
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> trellis,
                         TrellisFileReader::Open(trellis_path));
  const TrellisParams& trellis_params = trellis->params();
  if (trellis_params.archive_identity != archive->summary().identity ||
      trellis_params.frame_count != archive->frame_count()) {
    return Status::InvalidArgument(trellis_path +
                                   " was built from another archive or another "
                                   "version of " +
                                   archive_path + " (run `motifmine trellis` again)");
  }

  GrowOptions grow;
  grow.branch = options.branch;
  grow.all_branches = options.all_branches;
  grow.min_length = options.min_length_frames > 0
                        ? options.min_length_frames
                        : MinLengthFrames(options.min_length_seconds, archive->fps());
  MOTIF_RETURN_IF_ERROR(ValidateGrowOptions(grow));

  PathsReport report;
  report.paths_path = paths_path;
  report.trellis_entries = trellis->neighbour_count();
  report.params.trellis_identity = trellis->identity();
  report.params.archive_identity = trellis_params.archive_identity;
  report.params.frame_count = trellis_params.frame_count;
  report.params.branch = grow.branch;
  report.params.min_length = grow.min_length;
  report.params.all_branches = grow.all_branches;

  // A valid paths file grown from this trellis with these parameters is the answer already; a
  // damaged or stale one is replaced.
  std::error_code error;
  if (std::filesystem::exists(paths_path, error)) {
    Result<std::unique_ptr<PathsFileReader>> existing = PathsFileReader::Open(paths_path);
    if (existing.ok() && (*existing)->params() == report.params) {
      report.reused = true;
      report.candidates = (*existing)->candidates().size();
      return report;
    }
  }

  std::vector<uint64_t> clip_starts;
  clip_starts.reserve(archive->clips().size());
  for (const ClipInfo& clip : archive->clips()) clip_starts.push_back(clip.first_frame);
  auto start = std::chrono::steady_clock::now();
  MOTIF_ASSIGN_OR_RETURN(std::vector<PathCandidate> candidates,
                         GrowPaths(*trellis, clip_starts, grow, options.progress, &report.stats));
  report.grow_seconds = SecondsSince(start);
  report.candidates = candidates.size();
  start = std::chrono::steady_clock::now();
  MOTIF_RETURN_IF_ERROR(WritePathsFile(paths_path, report.params, candidates));
  report.write_seconds = SecondsSince(start);
  return report;
}

}  // namespace motif
