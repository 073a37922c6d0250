#include "formats/frame_file/frame_file_writer.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <system_error>
#include <unordered_set>

#include "common/file_util.h"
#include "common/mapped_file.h"
#include "formats/frame_file/archive_loader.h"
#include "formats/frame_file/block_codec.h"

#include "common/file_lock.h"

namespace motif {

using frame_file::ArchiveMetadata;
using frame_file::BlockHandle;
using frame_file::ColumnEncoding;
using frame_file::ColumnSpec;
using frame_file::CommitSlot;
using frame_file::Footer;
using frame_file::LoadedArchive;

namespace {

// A new archive's folder must exist; said of the archive, as `export` says it of its file, not
// of the temporary file the archive is first written to.
Status CheckFolderExists(const std::string& path) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::error_code error;
  if (folder.empty() || std::filesystem::is_directory(folder, error)) return Status::Ok();
  return Status::IOError(path + ": cannot create the archive: the folder " + folder.string() +
                         " does not exist");
}

// Maps `path` read-only just long enough to validate it and copy out what an append needs.
Result<LoadedArchive> LoadArchiveFile(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<MappedFile> file, MappedFile::Open(path));
  Result<LoadedArchive> loaded = frame_file::LoadArchive(path, file->data(), file->size());
  if (!loaded.ok()) return file->ExplainRead(loaded.status());
  return loaded;
}

Status ValidateOptions(const FrameFileWriterOptions& options, uint32_t joint_count) {
  if (options.file_system == nullptr) return Status::InvalidArgument("no file system given");
  const uint64_t stride = FrameLayout{joint_count}.stride();
  if (options.block_frames == 0 || options.block_frames > frame_file::kMaxBlockFrames ||
      options.block_frames * stride * 4 > frame_file::kMaxBlockRawBytes) {
    return Status::InvalidArgument("block size of " + std::to_string(options.block_frames) +
                                   " frames is 0 or too large");
  }
  if (!frame_file::IsValidZstdLevel(options.zstd_level)) {
    return Status::InvalidArgument("zstd level " + std::to_string(options.zstd_level) +
                                   " is out of range");
  }
  return Status::Ok();
}

bool AllFinite(const std::array<double, 3>& values) {
  return std::isfinite(values[0]) && std::isfinite(values[1]) && std::isfinite(values[2]);
}

bool AllFinite(const std::vector<std::array<float, 3>>& triples) {
  for (const auto& triple : triples) {
    for (float value : triple) {
      if (!std::isfinite(value)) return false;
    }
  }
  return true;
}

}  // namespace

class FrameFileWriter::Impl {
 public:
  enum class Mode { kCreate, kAppend };

  Impl(Mode mode, std::string path, const FrameFileWriterOptions& options)
      : mode_(mode), path_(std::move(path)), options_(options), fs_(options.file_system) {}
  ~Impl() {
    if (!committed_) Cleanup();
    // Commit closed the file and checked it; otherwise the write is abandoned: nothing to report.
    if (file_) (void)file_->Close();
    lock_.Release();
  }

  // Create: everything but the file (opened by the caller).
  void InitNew(const Skeleton& skeleton, double fps) {
    metadata_.fps = fps;
    metadata_.joint_count = static_cast<uint32_t>(skeleton.joint_count());
    metadata_.block_frames = options_.block_frames;
    metadata_.skeleton = skeleton;
    frame_file::ColumnDefaults defaults;
    defaults.quaternion_step = options_.quaternion_step;
    defaults.height_step = options_.height_step;
    defaults.velocity_step = options_.velocity_step;
    defaults.heading_step = options_.heading_step;
    defaults.lossless = options_.lossless;
    metadata_.columns = frame_file::DefaultColumns(metadata_.joint_count, defaults);
    write_path_ = TemporaryPathFor(path_);
    generation_ = 1;
    slot_to_write_ = 0;
    committed_length_ = 0;
    write_offset_ = frame_file::kHeaderBytes;
    InitBuffers();
  }

  // Append: continue the committed version `archive`.
  void InitAppend(LoadedArchive archive) {
    header_ = archive.header;
    metadata_ = std::move(archive.metadata);
    write_path_ = path_;
    generation_ = archive.max_generation + 1;
    slot_to_write_ = 1 - archive.active_slot;
    committed_length_ = archive.slot.committed_length;
    write_offset_ = committed_length_;
    for (const ClipInfo& clip : metadata_.clips) names_.insert(clip.name);
    InitBuffers();
  }

  Status OpenFile() {
    if (mode_ == Mode::kCreate) MOTIF_RETURN_IF_ERROR(CheckFolderExists(path_));
    const OpenMode open_mode =
        mode_ == Mode::kCreate ? OpenMode::kCreateExclusive : OpenMode::kExisting;
    MOTIF_ASSIGN_OR_RETURN(file_, fs_->OpenWritable(write_path_, open_mode));
    if (mode_ == Mode::kCreate) temp_exists_ = true;
    if (mode_ == Mode::kAppend) {
      MOTIF_ASSIGN_OR_RETURN(const uint64_t size, file_->Size());
      if (size > committed_length_) {
        // The tail of an interrupted append: readers ignore it; drop it before writing after it.
        Status truncated = file_->Truncate(committed_length_);
        if (!truncated.ok()) {
          (void)file_->Close();  // `truncated` is the error to report
          file_.reset();
          return truncated;
        }
      }
    }
    return Status::Ok();
  }

  ExclusiveFileLock& lock() { return lock_; }
  const ArchiveMetadata& metadata() const { return metadata_; }
  uint64_t frame_count() const { return next_frame_; }

  Status AppendClip(const ClipFrames& clip) {
    MOTIF_RETURN_IF_ERROR(CheckUsable());
    MOTIF_RETURN_IF_ERROR(CheckClip(clip));
    MOTIF_RETURN_IF_ERROR(BeginClip(clip.info));
    MOTIF_RETURN_IF_ERROR(BufferRows(clip.rows.data(), clip.info.frame_count));
    return EndClip();
  }

  Status CheckClip(const ClipFrames& clip) const {
    MOTIF_RETURN_IF_ERROR(CheckFrames(clip));
    return CheckClipInfo(clip.info);
  }

  // The rows alone: their count, and every value storable in its column.
  Status CheckFrames(const ClipFrames& clip) const {
    const std::string what = "clip \"" + clip.info.name + "\"";
    if (clip.info.frame_count == 0) return Invalid(what + " has no frames");
    const uint64_t stride = metadata_.layout().stride();
    if (clip.info.frame_count > clip.rows.size() / stride ||
        clip.rows.size() != clip.info.frame_count * stride) {
      return Invalid(what + " has " + std::to_string(clip.rows.size()) + " floats for " +
                     std::to_string(clip.info.frame_count) + " frames of " +
                     std::to_string(stride));
    }
    return CheckRows(clip.info.name, clip.rows.data(), clip.info.frame_count, 0);
  }

  Status BeginClip(const ClipInfo& info) {
    MOTIF_RETURN_IF_ERROR(CheckUsable());
    MOTIF_RETURN_IF_ERROR(CheckClipInfo(info));
    open_clip_ = info;
    open_clip_->first_frame = next_frame_;
    open_clip_->frame_count = 0;
    return Status::Ok();
  }

  Status AppendFrames(const float* rows, size_t frame_count) {
    MOTIF_RETURN_IF_ERROR(CheckUsable());
    if (!open_clip_) return Invalid("AppendFrames without BeginClip");
    if (frame_count == 0) return Status::Ok();
    if (rows == nullptr) return Invalid("AppendFrames given no rows");
    MOTIF_RETURN_IF_ERROR(CheckRows(open_clip_->name, rows, frame_count, open_clip_->frame_count));
    MOTIF_RETURN_IF_ERROR(BufferRows(rows, frame_count));
    return Status::Ok();
  }

  Status EndClip() {
    MOTIF_RETURN_IF_ERROR(CheckUsable());
    if (!open_clip_) return Invalid("EndClip without BeginClip");
    ClipInfo clip = std::move(*open_clip_);
    open_clip_.reset();
    if (clip.frame_count == 0) return Invalid("clip \"" + clip.name + "\" has no frames");
    names_.insert(clip.name);
    metadata_.clips.push_back(std::move(clip));
    return Status::Ok();
  }

  Status Commit() {
    MOTIF_RETURN_IF_ERROR(CheckUsable());
    if (open_clip_) {
      return Invalid("clip \"" + open_clip_->name + "\" is still open: call EndClip first");
    }
    Status status = WriteCommit();
    closed_ = true;
    if (!status.ok()) return Fail(status);
    committed_ = true;
    lock_.Release();
    return Status::Ok();
  }

 private:
  void InitBuffers() {
    stride_ = metadata_.layout().stride();
    encoder_.emplace(metadata_.columns, metadata_.joint_count, options_.zstd_level);
    buffer_.assign(static_cast<size_t>(options_.block_frames) * stride_, 0.0f);
    next_frame_ = metadata_.frame_count;
    column_of_float_.assign(stride_, 0);
    for (size_t column_idx = 0; column_idx < metadata_.columns.size(); ++column_idx) {
      const ColumnSpec& column = metadata_.columns[column_idx];
      for (uint32_t component = 0; component < column.component_count; ++component) {
        column_of_float_[column.row_offset + component] = column_idx;
      }
    }
  }

  Status Invalid(const std::string& message) const {
    return Status::InvalidArgument(path_ + ": " + message);
  }

  Status CheckUsable() const {
    if (!failure_.ok()) return failure_;
    if (closed_) return Invalid("the writer is closed (committed or failed)");
    return Status::Ok();
  }

  Status CheckClipInfo(const ClipInfo& info) const {
    const std::string what = "clip \"" + info.name + "\"";
    if (open_clip_) return Invalid("clip \"" + open_clip_->name + "\" is still open");
    if (info.name.empty()) return Invalid("a clip needs a name");
    if (names_.count(info.name) != 0) {
      return Invalid(what + ": a clip of that name is already in the archive");
    }
    const size_t joint_count = metadata_.joint_count;
    if (info.joint_offsets.size() != joint_count || info.end_sites.size() != joint_count) {
      return Invalid(what + " has " + std::to_string(info.joint_offsets.size()) +
                     " joint offsets and " + std::to_string(info.end_sites.size()) +
                     " end sites, the archive " + std::to_string(joint_count) + " joints");
    }
    if (!(std::fabs(info.fps - metadata_.fps) <= 1e-9 * metadata_.fps)) {
      return Invalid(what + " is at " + std::to_string(info.fps) + " fps, the archive at " +
                     std::to_string(metadata_.fps) + " (resample it first)");
    }
    if (!std::isfinite(info.source_fps) || !std::isfinite(info.meters_per_unit) ||
        !AllFinite(info.start_position) || !AllFinite(info.joint_offsets) ||
        !AllFinite(info.end_sites)) {
      return Invalid(what + " has a non-finite rate, start position, offset or end site");
    }
    if (!info.source_joint_names.empty() && info.source_joint_names.size() != joint_count) {
      return Invalid(what + " has " + std::to_string(info.source_joint_names.size()) +
                     " source joint names, the archive " + std::to_string(joint_count) + " joints");
    }
    for (const std::string& name : info.source_joint_names) {
      if (name.empty()) return Invalid(what + " has an empty source joint name");
    }
    return Status::Ok();
  }

  // Every value must be storable with its column's encoding; checked before anything is
  // buffered, so a rejected call leaves the writer as it was.
  Status CheckRows(const std::string& clip_name, const float* rows, size_t frame_count,
                   uint64_t first_clip_frame) const {
    for (size_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
      const float* row = rows + frame_idx * stride_;
      for (size_t float_idx = 0; float_idx < stride_; ++float_idx) {
        const ColumnEncoding& encoding = metadata_.columns[column_of_float_[float_idx]].encoding;
        if (frame_file::IsEncodable(encoding, row[float_idx])) continue;
        const std::string where = "clip \"" + clip_name + "\" frame " +
                                  std::to_string(first_clip_frame + frame_idx) + ", row float " +
                                  std::to_string(float_idx) + " (column " +
                                  std::to_string(column_of_float_[float_idx]) + ")";
        if (!std::isfinite(row[float_idx])) return Invalid(where + ": value is not finite");
        return Invalid(where + ": value " + std::to_string(row[float_idx]) +
                       " overflows int32 when quantised with step " +
                       std::to_string(encoding.step));
      }
    }
    return Status::Ok();
  }

  Status BufferRows(const float* rows, size_t frame_count) {
    const uint32_t block_frames = options_.block_frames;
    size_t done = 0;
    while (done < frame_count) {
      const size_t take = std::min<size_t>(frame_count - done, block_frames - buffered_frames_);
      std::copy(rows + done * stride_, rows + (done + take) * stride_,
                buffer_.begin() + buffered_frames_ * stride_);
      buffered_frames_ += static_cast<uint32_t>(take);
      next_frame_ += take;
      open_clip_->frame_count += take;
      done += take;
      if (buffered_frames_ == block_frames) {
        Status flushed = FlushBlock();
        if (!flushed.ok()) return Fail(flushed);
      }
    }
    return Status::Ok();
  }

  // Encodes the buffered frames as one block and writes it at the end.
  Status FlushBlock() {
    if (buffered_frames_ == 0) return Status::Ok();
    BlockHandle block;
    block.first_frame = next_frame_ - buffered_frames_;
    block.frame_count = buffered_frames_;
    MOTIF_RETURN_IF_ERROR(
        encoder_->Encode(buffer_.data(), buffered_frames_, block.first_frame, &block_bytes_));
    block.offset = write_offset_;
    block.bytes = block_bytes_.size();
    block.checksum = frame_file::Checksum64(block_bytes_.data(), block_bytes_.size());
    dirty_ = true;
    MOTIF_RETURN_IF_ERROR(file_->WriteAt(write_offset_, block_bytes_.data(), block_bytes_.size()));
    write_offset_ += block.bytes;
    metadata_.blocks.push_back(block);
    buffered_frames_ = 0;
    return Status::Ok();
  }

  // Commit protocol (docs/formats/frame_file.md, "Commit and append"). The commit point is the
  // rename (create) or the slot write (append); before it nothing is visible.
  Status WriteCommit() {
    MOTIF_RETURN_IF_ERROR(FlushBlock());
    metadata_.frame_count = next_frame_;
    std::string tail;
    metadata_.EncodeTo(&tail);
    Footer footer;
    footer.generation = generation_;
    footer.metadata_offset = write_offset_;
    footer.metadata_bytes = tail.size();
    footer.metadata_checksum = frame_file::Checksum64(tail.data(), tail.size());
    footer.EncodeTo(&tail);
    CommitSlot slot;
    slot.generation = generation_;
    slot.committed_length = write_offset_ + tail.size();
    slot.footer_offset = slot.committed_length - frame_file::kFooterBytes;
    dirty_ = true;
    MOTIF_RETURN_IF_ERROR(file_->WriteAt(write_offset_, tail.data(), tail.size()));
    write_offset_ += tail.size();

    if (mode_ == Mode::kCreate) {
      header_ = frame_file::FileHeader();
      header_.slots[0] = slot;
      std::string header_bytes;
      header_.EncodeTo(&header_bytes);
      MOTIF_RETURN_IF_ERROR(file_->WriteAt(0, header_bytes.data(), header_bytes.size()));
      MOTIF_RETURN_IF_ERROR(file_->Sync());
      MOTIF_RETURN_IF_ERROR(file_->Close());
      // Not over an archive another writer created meanwhile (two imports starting one
      // archive): this run changed nothing, and retried it appends.
      Status renamed = fs_->RenameNoReplace(write_path_, path_);
      if (renamed.IsBusy()) {
        return Status::Busy(path_ +
                            ": created by another writer while this one was writing it; not "
                            "replacing it (run again to append)");
      }
      MOTIF_RETURN_IF_ERROR(renamed);
      // The archive is in place (a failed directory sync only risks its durability).
      commit_point_reached_ = true;
      temp_exists_ = false;
      return fs_->SyncParentDir(path_);
    }
    MOTIF_RETURN_IF_ERROR(file_->Sync());
    std::string slot_bytes;
    slot.EncodeTo(&slot_bytes);
    // From here on the new version may be visible: never truncate it away.
    commit_point_reached_ = true;
    MOTIF_RETURN_IF_ERROR(file_->WriteAt(frame_file::kSlotOffsets[slot_to_write_],
                                         slot_bytes.data(), slot_bytes.size()));
    MOTIF_RETURN_IF_ERROR(file_->Sync());
    return file_->Close();
  }

  // Records a failure (every later call returns it) and rolls back what it can.
  Status Fail(const Status& status) {
    failure_ = status;
    closed_ = true;
    Cleanup();
    return status;
  }

  // Best effort, and retried at destruction if it failed: drops everything written since
  // opening (the temporary file of a create, the tail of an append) unless the commit point was
  // reached, then lets go of the file and the lock.
  void Cleanup() {
    if (mode_ == Mode::kCreate) {
      if (file_) (void)file_->Close();  // the temporary file is removed next
      if (temp_exists_ && !commit_point_reached_ && fs_->Remove(write_path_).ok()) {
        temp_exists_ = false;
      }
      return;
    }
    if (dirty_ && !commit_point_reached_ && file_ && file_->Truncate(committed_length_).ok()) {
      dirty_ = false;
    }
    if (!dirty_ || commit_point_reached_) {
      // Nothing of ours is left to lose in it (truncated back, or committed and synced).
      if (file_) (void)file_->Close();
      lock_.Release();
    }
  }

  Mode mode_;
  std::string path_;
  std::string write_path_;  // the temporary file (create) or the archive (append)
  FrameFileWriterOptions options_;
  FileSystem* fs_;
  std::unique_ptr<WritableFile> file_;
  ExclusiveFileLock lock_;
  frame_file::FileHeader header_;
  ArchiveMetadata metadata_;  // committed plus appended clips and blocks
  uint64_t generation_ = 0;
  int slot_to_write_ = 0;
  uint64_t committed_length_ = 0;  // of the version this writer started from (0: none)
  uint64_t write_offset_ = 0;      // where the next block goes
  size_t stride_ = 0;
  std::vector<size_t> column_of_float_;  // row float -> column index
  std::optional<frame_file::BlockEncoder> encoder_;
  std::vector<float> buffer_;  // block_frames rows
  uint32_t buffered_frames_ = 0;
  uint64_t next_frame_ = 0;  // global index of the next frame appended
  std::string block_bytes_;
  std::optional<ClipInfo> open_clip_;
  std::unordered_set<std::string> names_;
  Status failure_;
  bool closed_ = false;
  bool committed_ = false;
  bool temp_exists_ = false;           // create: the temporary file is ours to remove
  bool dirty_ = false;                 // append: bytes written after the committed end
  bool commit_point_reached_ = false;  // the rename / slot write was attempted
};

Result<std::unique_ptr<FrameFileWriter>> FrameFileWriter::Create(
    const std::string& path, const Skeleton& skeleton, double fps,
    const FrameFileWriterOptions& options) {
  std::error_code error;
  if (std::filesystem::exists(path, error)) {
    return Status::InvalidArgument(path + ": already exists; open it for append instead");
  }
  Status valid = skeleton.Validate();
  if (!valid.ok()) return valid.WithContext(path);
  if (skeleton.joint_count() > frame_file::kMaxJoints) {
    return Status::InvalidArgument(path + ": more than " + std::to_string(frame_file::kMaxJoints) +
                                   " joints");
  }
  if (!std::isfinite(fps) || !(fps > 0)) {
    return Status::InvalidArgument(path + ": fps " + std::to_string(fps) +
                                   " is not finite and > 0");
  }
  valid = ValidateOptions(options, static_cast<uint32_t>(skeleton.joint_count()));
  if (!valid.ok()) return valid.WithContext(path);
  const uint32_t joint_count = static_cast<uint32_t>(skeleton.joint_count());
  frame_file::ColumnDefaults defaults;
  defaults.quaternion_step = options.quaternion_step;
  defaults.height_step = options.height_step;
  defaults.velocity_step = options.velocity_step;
  defaults.heading_step = options.heading_step;
  defaults.lossless = options.lossless;
  valid =
      frame_file::ValidateColumns(frame_file::DefaultColumns(joint_count, defaults), joint_count);
  if (!valid.ok()) return valid.WithContext(path);

  auto impl = std::make_unique<Impl>(Impl::Mode::kCreate, path, options);
  impl->InitNew(skeleton, fps);
  MOTIF_RETURN_IF_ERROR(impl->OpenFile());
  return std::unique_ptr<FrameFileWriter>(new FrameFileWriter(std::move(impl)));
}

Result<std::unique_ptr<FrameFileWriter>> FrameFileWriter::OpenForAppend(
    const std::string& path, const FrameFileWriterOptions& options) {
  auto impl = std::make_unique<Impl>(Impl::Mode::kAppend, path, options);
  MOTIF_RETURN_IF_ERROR(impl->lock().Acquire(path, "the archive is locked by another writer"));
  MOTIF_ASSIGN_OR_RETURN(LoadedArchive archive, LoadArchiveFile(path));
  if (!archive.fallback_reason.empty()) {
    return Status::Corruption(archive.fallback_reason +
                              "; refusing to append to an archive whose newest commit is damaged");
  }
  if (archive.header.format_minor > frame_file::kFormatMinor ||
      archive.footer.format_minor > frame_file::kFormatMinor) {
    return Status::NotSupported(path + ": format 1." + std::to_string(archive.footer.format_minor) +
                                " is newer than this writer's 1." +
                                std::to_string(frame_file::kFormatMinor) +
                                "; appending would drop what it added");
  }
  if (archive.max_generation == UINT64_MAX) {
    return Status::Corruption(path + ": commit generation " +
                              std::to_string(archive.max_generation) + " cannot be incremented");
  }
  Status valid = ValidateOptions(options, archive.metadata.joint_count);
  if (!valid.ok()) return valid.WithContext(path);
  impl->InitAppend(std::move(archive));
  MOTIF_RETURN_IF_ERROR(impl->OpenFile());
  return std::unique_ptr<FrameFileWriter>(new FrameFileWriter(std::move(impl)));
}

FrameFileWriter::FrameFileWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
FrameFileWriter::~FrameFileWriter() = default;

const Skeleton& FrameFileWriter::skeleton() const { return impl_->metadata().skeleton; }
double FrameFileWriter::fps() const { return impl_->metadata().fps; }
FrameLayout FrameFileWriter::layout() const { return impl_->metadata().layout(); }
uint64_t FrameFileWriter::frame_count() const { return impl_->frame_count(); }
const std::vector<ClipInfo>& FrameFileWriter::clips() const { return impl_->metadata().clips; }

Status FrameFileWriter::AppendClip(const ClipFrames& clip) { return impl_->AppendClip(clip); }
Status FrameFileWriter::CheckFrames(const ClipFrames& clip) const {
  return impl_->CheckFrames(clip);
}
Status FrameFileWriter::BeginClip(const ClipInfo& info) { return impl_->BeginClip(info); }
Status FrameFileWriter::AppendFrames(const float* rows, size_t frame_count) {
  return impl_->AppendFrames(rows, frame_count);
}
Status FrameFileWriter::EndClip() { return impl_->EndClip(); }
Status FrameFileWriter::Commit() { return impl_->Commit(); }

}  // namespace motif
