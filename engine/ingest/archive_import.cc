#include "engine/ingest/archive_import.h"

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <unordered_set>

#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "engine/ingest/duplicate_takes.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/import/skeleton_kind.h"
#include "formats/motion/body_retarget.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/resample.h"

namespace motif {

namespace {

// 120, 29.97: the rate as a person writes it ("%g"), not std::to_string's 120.000000.
std::string FormatFps(double fps) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", fps);
  return text;
}

}  // namespace
namespace {

// One take on its way through the pipeline.
struct TakeInFlight {
  size_t index = 0;
  Status status;
  std::optional<ClipFrames> clip;
  std::string mapped_from;  // the source's skeleton, when it was mapped onto the CMU body
};

// A skeleton as a person tells it apart: "a 43-joint skeleton (root 'hip')".
std::string SkeletonSummary(const Skeleton& skeleton) {
  return "a " + std::to_string(skeleton.joint_count()) + "-joint skeleton (root '" +
         (skeleton.joint_count() ? skeleton.joint(0).name : std::string()) + "')";
}

// A take of another family, for an archive on the CMU body: mapped onto it.
Status MapOntoArchiveBody(const Skeleton& archive, Take* take, std::string* mapped_from) {
  if (archive.family() != kCmuFamily || take->skeleton.family() == kCmuFamily) {
    return Status::Ok();
  }
  const std::string from = SkeletonSummary(take->skeleton);
  MOTIF_ASSIGN_OR_RETURN(*take, RetargetToCmuBody(*take));
  *mapped_from = from;
  return Status::Ok();
}

// Converts one parsed take (or its parse error) to the archive's skeleton and rate.
TakeInFlight PrepareTake(const TakeSource& source, size_t index, Result<Take> take,
                         const Skeleton& skeleton, double fps) {
  TakeInFlight item;
  item.index = index;
  if (!take.ok()) {
    item.status = take.status();
    return item;
  }
  item.status = MapOntoArchiveBody(skeleton, &take.value(), &item.mapped_from);
  if (!item.status.ok()) return item;
  item.status = ConformToSkeleton(skeleton, &take.value());
  if (!item.status.ok()) return item;
  if (take->frame_count() == 0) {
    item.status = Status::InvalidArgument(source.path + ": the take has no frames");
    return item;
  }
  item.clip = TakeToClipFrames(ResampleTake(*take, fps));
  return item;
}

// The takes read to create the archive (sources[0, size()), the last one the take that decided
// its skeleton and rate): the import uses them as they were read, so that each take file is read
// once and a file replaced meanwhile cannot give frames at another file's rate.
using TakesReadFirst = std::vector<Result<Take>>;

// A take that stops the import: its error with the option that would have let the others in
// (the tool says "--skip-bad", Python "skip_bad"); a mixed folder says what an archive holds.
Status StopForTake(const Status& status) {
  if (!status.option().empty()) return status;  // it names its own option already (asf)
  const bool other_family = status.message().find("skeleton family") != std::string::npos;
  const std::string why = other_family ? "an archive holds one skeleton family, and one made "
                                         "from a folder of several is on the CMU body; "
                                       : "";
  return Status::FromCode(status.code(),
                          status.message() + " (" + why + "skip_bad imports the other takes)")
      .WithOption("skip_bad");
}

// A message for the user, if the caller takes them (empty ones are not passed on).
void ImportNote(const ArchiveImportOptions& options, const std::string& message) {
  if (options.note) message.empty() ? void() : options.note(message);
}

// True when some take of `sources` has another skeleton than sources[first] (its skeleton read
// alone, ReadSkeletonKind; takes whose skeleton cannot be read do not count: they fail later).
bool MixesSkeletons(const std::vector<TakeSource>& sources, size_t first,
                    const ImportOptions& options) {
  const Result<std::string> kind = ReadSkeletonKind(sources[first], options);
  if (!kind.ok()) return false;
  for (size_t index = first + 1; index < sources.size(); ++index) {
    const Result<std::string> other = ReadSkeletonKind(sources[index], options);
    if (other.ok() && *other != *kind) return true;
  }
  return false;
}

// A new archive's writer; Busy when another import created the archive meanwhile.
Result<std::unique_ptr<FrameFileWriter>> CreateArchive(const std::string& archive_path,
                                                       const Skeleton& skeleton, double fps,
                                                       const FrameFileWriterOptions& options) {
  Result<std::unique_ptr<FrameFileWriter>> writer =
      FrameFileWriter::Create(archive_path, skeleton, fps, options);
  std::error_code error;
  if (!writer.ok() && std::filesystem::exists(archive_path, error)) {
    // Another import created it since the caller looked: the same race the writer's commit
    // reports as busy, lost earlier.
    return Status::Busy(archive_path +
                        ": created by another import while this one was starting; not "
                        "replacing it (run again to append)");
  }
  return writer;
}

// The archive's writer: appending to it when it exists, else creating it from the first take
// that imports, which decides the skeleton and, unless given, the rate (result->created). The
// takes read for that are kept in `read_first`.
Result<std::unique_ptr<FrameFileWriter>> OpenOrCreateArchive(const std::string& archive_path,
                                                             const std::vector<TakeSource>& sources,
                                                             const ArchiveImportOptions& options,
                                                             ArchiveImportResult* result,
                                                             TakesReadFirst* read_first) {
  FrameFileWriterOptions writer_options;
  writer_options.block_frames = options.block_frames;
  writer_options.file_system = options.file_system;
  std::error_code error;
  if (std::filesystem::exists(archive_path, error)) {
    return FrameFileWriter::OpenForAppend(archive_path, writer_options);
  }
  for (const TakeSource& source : sources) {
    read_first->push_back(ImportTake(source, options.import));
    if (read_first->back().ok() || !options.skip_bad) break;
  }
  if (!read_first->back().ok()) {
    return options.skip_bad ? read_first->back().status() : StopForTake(read_first->back().status());
  }
  const Take& read = *read_first->back();
  const bool mixed = read.skeleton.family() != kCmuFamily &&
                     MixesSkeletons(sources, read_first->size() - 1, options.import);
  // A mixed folder's archive is on the CMU body: the first take's mapping gives its skeleton
  // (the take itself is mapped again on its way in, and counted with the others).
  std::optional<Take> mapped_first;
  if (mixed) {
    Result<Take> mapped = RetargetToCmuBody(read);
    if (!mapped.ok()) return options.skip_bad ? mapped.status() : StopForTake(mapped.status());
    mapped_first = std::move(*mapped);
  }
  const Take& first = mapped_first ? *mapped_first : read;
  const double fps = options.fps > 0 ? options.fps : first.fps;
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileWriter> writer,
                         CreateArchive(archive_path, first.skeleton, fps, writer_options));
  result->created = true;
  ImportNote(options, "creating " + archive_path + ": skeleton " + first.skeleton.family() + " (" +
                          std::to_string(first.skeleton.joint_count()) + " joints), " +
                          FormatFps(fps) + " fps" +
                          (mixed ? "; the takes are of several skeleton families, each mapped "
                                   "onto the CMU body"
                                 : ""));
  return writer;
}

// The pipeline's last, serial stage: appends the prepared takes in discovery order, skipping
// those already in the archive (by content hash) and renaming those whose name is taken. A
// failure stops the import (stop(), first_error()) unless skip_bad lets it pass, named.
class ClipAppender {
 public:
  // `stored`: the archive before this import (null when it is being created).
  ClipAppender(FrameFileWriter* writer, const FrameFileReader* stored,
               const ArchiveImportOptions& options, uint64_t take_count, ArchiveImportResult* result)
      : writer_(writer),
        options_(options),
        take_count_(take_count),
        result_(result),
        duplicates_(stored, FrameLayout{static_cast<uint32_t>(writer->skeleton().joint_count())}) {
    for (const ClipInfo& clip : writer->clips()) {
      if (clip.content_hash != 0) known_hashes_.insert(clip.content_hash);
      known_names_.insert(clip.name);
    }
  }

  bool stopped() const { return stop_.load(); }
  const Status& first_error() const { return first_error_; }

  void Consume(TakeInFlight item) {
    if (stop_.load()) return;
    ++done_;
    if (options_.progress) options_.progress(done_, take_count_);
    if (!item.status.ok()) {
      ++result_->takes_failed;
      result_->failures.push_back(item.status.message());
      if (!options_.skip_bad) {
        Stop(StopForTake(item.status));
      } else {
        ImportNote(options_, "skipped: " + item.status.message());
      }
      return;
    }
    ClipFrames& clip = *item.clip;
    if (known_hashes_.count(clip.info.content_hash)) {
      ++result_->takes_already_present;
      ImportNote(options_, clip.info.source_path + ": already in the archive, skipped");
      return;
    }
    if (IsCopyOfAKnownClip(clip)) return;
    GiveUniqueName(&clip);
    if (!Append(clip) || item.mapped_from.empty()) return;
    ++result_->takes_mapped;
    if (mapped_kinds_.insert(item.mapped_from).second) {
      ImportNote(options_, clip.info.source_path + ": " + item.mapped_from +
                               ", mapped onto the CMU body (as are the other takes of it)");
    }
  }

 private:
  void Stop(const Status& status) {
    first_error_ = status;
    stop_.store(true);
  }

  // The same capture in another format (other bytes, the same frames): skipped, both named.
  bool IsCopyOfAKnownClip(const ClipFrames& clip) {
    Result<std::optional<ClipInfo>> copy = duplicates_.FindCopy(clip);
    if (!copy.ok()) {
      Stop(copy.status());
      return true;
    }
    // A bad take is reported as bad (by Append), even when its rotations copy another's.
    if (!copy->has_value() || !writer_->CheckFrames(clip).ok()) return false;
    ++result_->takes_already_present;
    ImportNote(options_, clip.info.source_path + ": the same frames as clip '" + (*copy)->name +
                             "' (" + (*copy)->source_path + "), skipped");
    return true;
  }

  // "<stem>~2" ("~3", ...) when a clip of that name exists already.
  void GiveUniqueName(ClipFrames* clip) {
    std::string name = clip->info.name;
    for (int suffix = 2; known_names_.count(name); ++suffix) {
      name = clip->info.name + "~" + std::to_string(suffix);
    }
    if (name != clip->info.name) {
      ImportNote(options_, clip->info.source_path + ": a clip named '" + clip->info.name +
                               "' exists already; stored as '" + name + "'");
      clip->info.name = name;
    }
  }

  // True when the clip was stored.
  bool Append(const ClipFrames& clip) {
    Status status = writer_->AppendClip(clip);
    if (status.IsInvalidArgument()) {
      // The take's own values (a root position of 1e308 gives an infinite velocity): a bad take
      // like any other, named by its file. The writer refused it before storing anything and
      // stays usable.
      status = status.WithContext(clip.info.source_path);
      ++result_->takes_failed;
      result_->failures.push_back(status.message());
      if (options_.skip_bad) {
        ImportNote(options_, "skipped: " + status.message());
        return false;
      }
    }
    if (!status.ok()) {
      Stop(status);
      return false;
    }
    known_hashes_.insert(clip.info.content_hash);
    known_names_.insert(clip.info.name);
    duplicates_.Add(clip);
    ++result_->takes_imported;
    result_->frames_added += clip.info.frame_count;
    return true;
  }

  FrameFileWriter* writer_;
  const ArchiveImportOptions& options_;
  const uint64_t take_count_;
  ArchiveImportResult* result_;
  std::unordered_set<uint64_t> known_hashes_;
  std::unordered_set<std::string> known_names_;
  std::unordered_set<std::string> mapped_kinds_;  // the skeletons a note has named
  DuplicateTakes duplicates_;
  Status first_error_;
  std::atomic<bool> stop_{false};
  uint64_t done_ = 0;
};

// Parses and converts the takes in parallel (at most twice the threads in flight) and hands
// them to `appender` in discovery order; nothing new starts once it has stopped.
void RunImportPipeline(const std::vector<TakeSource>& sources, const Skeleton& skeleton, double fps,
                       const ArchiveImportOptions& options, TakesReadFirst* read_first,
                       ClipAppender* appender) {
  size_t next_source = 0;
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  const size_t max_in_flight = 2 * static_cast<size_t>(arena.max_concurrency());
  auto next = [&](tbb::flow_control& control) -> size_t {
    if (next_source >= sources.size() || appender->stopped()) {
      control.stop();
      return 0;
    }
    return next_source++;
  };
  auto prepare = [&](size_t index) {
    if (appender->stopped()) return TakeInFlight{index, Status::Ok(), std::nullopt, {}};
    // Each index comes once: moving out of read_first races with nothing.
    Result<Take> take = index < read_first->size() ? std::move((*read_first)[index])
                                                   : ImportTake(sources[index], options.import);
    return PrepareTake(sources[index], index, std::move(take), skeleton, fps);
  };
  auto consume = [&](TakeInFlight item) { appender->Consume(std::move(item)); };
  arena.execute([&] {
    tbb::parallel_pipeline(
        max_in_flight,
        tbb::make_filter<void, size_t>(tbb::filter_mode::serial_in_order, next) &
            tbb::make_filter<size_t, TakeInFlight>(tbb::filter_mode::parallel, prepare) &
            tbb::make_filter<TakeInFlight, void>(tbb::filter_mode::serial_in_order, consume));
  });
}

}  // namespace

Result<ArchiveImportResult> ImportIntoArchive(const std::string& archive_path,
                                              const std::vector<std::string>& inputs,
                                              const ArchiveImportOptions& options) {
  MOTIF_ASSIGN_OR_RETURN(std::vector<TakeSource> sources, DiscoverTakes(inputs, options.import));
  if (sources.empty()) {
    // Name what was searched: "x.bvh" may be a folder, searched as one.
    std::string searched;
    for (const std::string& input : inputs) {
      searched += (searched.empty() ? "" : ", ") + input;
      std::error_code error;
      if (std::filesystem::is_directory(input, error)) searched += " (a folder)";
    }
    return Status::InvalidArgument("no .bvh or .amc takes found in " + searched);
  }
  return ImportTakesIntoArchive(archive_path, sources, options);
}

Result<ArchiveImportResult> ImportTakesIntoArchive(const std::string& archive_path,
                                                   const std::vector<TakeSource>& sources,
                                                   const ArchiveImportOptions& options) {
  ArchiveImportResult result;
  result.takes_found = sources.size();
  if (sources.empty()) return Status::InvalidArgument("no takes to import");
  TakesReadFirst read_first;
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileWriter> writer,
                         OpenOrCreateArchive(archive_path, sources, options, &result, &read_first));
  const Skeleton skeleton = writer->skeleton();
  const double fps = writer->fps();
  result.fps = fps;
  {
    // The archive as it was: its clips are compared with the new takes (DuplicateTakes).
    std::unique_ptr<FrameFileReader> stored;
    if (!result.created) {
      Result<std::unique_ptr<FrameFileReader>> opened = FrameFileReader::Open(archive_path);
      if (opened.ok()) stored = std::move(*opened);
    }
    ClipAppender appender(writer.get(), stored.get(), options, sources.size(), &result);
    RunImportPipeline(sources, skeleton, fps, options, &read_first, &appender);
    // The writer's destructor abandons the append.
    if (!appender.first_error().ok()) return appender.first_error();
  }
  // An append that adds nothing is not committed: the archive keeps its generation and identity,
  // so a rerun (after a kill past the commit, or from cron) leaves it and what was built on it
  // as they are.
  if (result.created || result.takes_imported > 0) MOTIF_RETURN_IF_ERROR(writer->Commit());
  result.archive_clips = writer->clips().size();
  result.archive_frames = writer->frame_count();
  return result;
}

}  // namespace motif
