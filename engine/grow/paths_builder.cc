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

std::string DefaultPathsPath(const std::string& archive_path) {
  std::filesystem::path path(archive_path);
  if (path.extension() == ".mfs") path.replace_extension("");
  return path.string() + ".mpa";
}

uint64_t MinLengthFrames(double seconds, double fps) {
  const double frames = std::round(seconds * fps);
  return frames < 1 ? 1 : static_cast<uint64_t>(frames);
}

namespace {

// The grower's options for an archive at `fps`; InvalidOption naming the parameter.
Result<GrowOptions> GrowOptionsFor(const PathsOptions& options, double fps) {
  if (options.min_length_frames == 0 &&
      !(options.min_length_seconds > 0 && std::isfinite(options.min_length_seconds))) {
    return Status::InvalidOption("min-length", "must be positive");
  }
  GrowOptions grow;
  grow.branch = options.branch;
  grow.all_branches = options.all_branches;
  grow.min_length = options.min_length_frames > 0
                        ? options.min_length_frames
                        : MinLengthFrames(options.min_length_seconds, fps);
  MOTIF_RETURN_IF_ERROR(ValidateGrowOptions(grow));
  return grow;
}

std::vector<uint64_t> ClipStarts(const FrameFileReader& archive) {
  std::vector<uint64_t> clip_starts;
  clip_starts.reserve(archive.clips().size());
  for (const ClipInfo& clip : archive.clips()) clip_starts.push_back(clip.first_frame);
  return clip_starts;
}

PathsParams ParamsOf(const TrellisFileReader& trellis, const GrowOptions& grow) {
  PathsParams params;
  params.trellis_identity = trellis.identity();
  params.archive_identity = trellis.params().archive_identity;
  params.frame_count = trellis.params().frame_count;
  params.branch = grow.branch;
  params.min_length = grow.min_length;
  params.all_branches = grow.all_branches;
  return params;
}

// A valid paths file grown from this trellis with these parameters is the answer already; a
// damaged or stale one is replaced.
bool ReuseExisting(const std::string& paths_path, PathsReport* report) {
  std::error_code error;
  if (!std::filesystem::exists(paths_path, error)) return false;
  Result<std::unique_ptr<PathsFileReader>> existing = PathsFileReader::Open(paths_path);
  if (!existing.ok() || !((*existing)->params() == report->params)) return false;
  report->reused = true;
  report->candidates = (*existing)->candidates().size();
  return true;
}

}  // namespace

Result<PathsReport> BuildPaths(const FrameFileReader& archive, const TrellisFileReader& trellis,
                               const std::string& paths_path, const PathsOptions& options) {
  const TrellisParams& trellis_params = trellis.params();
  if (trellis_params.archive_identity != archive.summary().identity ||
      trellis_params.frame_count != archive.frame_count()) {
    return Status::InvalidArgument(trellis.path() +
                                   " was built from another archive or another "
                                   "version of " +
                                   archive.path() + " (run `motifmine trellis` again)");
  }
  MOTIF_ASSIGN_OR_RETURN(const GrowOptions grow, GrowOptionsFor(options, archive.fps()));
  PathsReport report;
  report.paths_path = paths_path;
  report.trellis_entries = trellis.neighbour_count();
  report.params = ParamsOf(trellis, grow);
  if (ReuseExisting(paths_path, &report)) return report;

  auto start = std::chrono::steady_clock::now();
  MOTIF_ASSIGN_OR_RETURN(
      std::vector<PathCandidate> candidates,
      GrowPaths(trellis, ClipStarts(archive), grow, options.progress, &report.stats));
  report.grow_seconds = SecondsSince(start);
  report.candidates = candidates.size();
  start = std::chrono::steady_clock::now();
  MOTIF_RETURN_IF_ERROR(WritePathsFile(paths_path, report.params, candidates));
  report.write_seconds = SecondsSince(start);
  return report;
}

Result<PathsReport> BuildPaths(const std::string& archive_path, const std::string& trellis_path,
                               const std::string& paths_path, const PathsOptions& options) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileReader> archive,
                         FrameFileReader::OpenVersion(archive_path, options.archive_version));
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> trellis,
                         TrellisFileReader::Open(trellis_path));
  return BuildPaths(*archive, *trellis, paths_path, options);
}

StreamedPaths::StreamedPaths(std::unique_ptr<PathGrower> grower, GrowOptions grow,
                             uint64_t frame_count, uint64_t archive_identity)
    : grower_(std::move(grower)),
      grow_(grow),
      frame_count_(frame_count),
      archive_identity_(archive_identity) {}

Result<std::unique_ptr<StreamedPaths>> StreamedPaths::Create(const FrameFileReader& archive,
                                                             const PathsOptions& options) {
  MOTIF_ASSIGN_OR_RETURN(const GrowOptions grow, GrowOptionsFor(options, archive.fps()));
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<PathGrower> grower,
                         PathGrower::Create(archive.frame_count(), ClipStarts(archive), grow));
  return std::unique_ptr<StreamedPaths>(new StreamedPaths(
      std::move(grower), grow, archive.frame_count(), archive.summary().identity));
}

Status StreamedPaths::AddBlock(uint64_t first_column,
                               const std::vector<std::vector<Neighbour>>& columns) {
  if (grower_->next_column() != first_column) return Status::Ok();  // resumed: BuildPaths
  for (const std::vector<Neighbour>& column : columns) {
    MOTIF_RETURN_IF_ERROR(grower_->AddColumn(column.data(), column.size()));
  }
  return Status::Ok();
}

Status StreamedPaths::FinishIfComplete(const TrellisFileReader& trellis,
                                       const std::string& paths_path) {
  if (grower_->next_column() != frame_count_ || frame_count_ == 0) return Status::Ok();
  MOTIF_ASSIGN_OR_RETURN(std::vector<PathCandidate> candidates, grower_->Finish());
  PathsParams params = ParamsOf(trellis, grow_);
  params.archive_identity = archive_identity_;
  return WritePathsFile(paths_path, params, candidates);
}

}  // namespace motif
