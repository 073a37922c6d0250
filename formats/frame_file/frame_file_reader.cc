#include "formats/frame_file/frame_file_reader.h"

#include <algorithm>
#include <mutex>

#include "common/mapped_file.h"
#include "formats/frame_file/archive_loader.h"
#include "formats/frame_file/block_codec.h"

namespace motif {

using frame_file::BlockHandle;
using frame_file::Hex;

class FrameFileReader::Impl {
 public:
  class Stream;

  std::string path;
  std::unique_ptr<MappedFile> file;
  const uint8_t* data = nullptr;
  uint64_t size = 0;
  frame_file::LoadedArchive archive;

  const frame_file::ArchiveMetadata& metadata() const { return archive.metadata; }

  // Index of the block holding `frame_idx` (< frame_count).
  size_t FindBlock(uint64_t frame_idx) const {
    const auto& blocks = metadata().blocks;
    auto after = std::upper_bound(
        blocks.begin(), blocks.end(), frame_idx,
        [](uint64_t frame, const BlockHandle& block) { return frame < block.first_frame; });
    return static_cast<size_t>(after - blocks.begin()) - 1;
  }

  Status DecodeBlock(size_t block_idx, std::vector<float>* rows) const {
    const BlockHandle& block = metadata().blocks[block_idx];
    Status status = frame_file::DecodeBlock(metadata().columns, metadata().joint_count, block,
                                            data + block.offset, rows);
    if (!status.ok()) {
      status = status.WithContext(path + ": block " + std::to_string(block_idx) + " at offset " +
                                  Hex(block.offset));
    }
    return file->ExplainRead(status);  // zeros past a new end are the cut's fault, not the block's
  }

  // Gives the whole pages of file bytes [begin_offset, end_offset) back to the kernel (the
  // stream has decoded them) and returns the page-aligned end actually released. The pages
  // are re-read from the file if touched again, so sharing a page with the next block is safe.
  uint64_t ReleasePages(uint64_t begin_offset, uint64_t end_offset) const {
    return file->ReleasePages(begin_offset, end_offset);
  }
};

// Walks blocks in order; holds one decoded block.
class FrameFileReader::Impl::Stream final : public FrameStream {
 public:
  Stream(const Impl* impl, uint64_t first_frame, uint64_t end_frame)
      : impl_(impl), next_frame_(first_frame), end_frame_(end_frame) {
    if (next_frame_ < end_frame_) {
      block_idx_ = impl_->FindBlock(next_frame_);
      released_until_ = impl_->metadata().blocks[block_idx_].offset;
    }
  }

  Result<bool> Next() override {
    run_first_ = 0;
    run_count_ = 0;
    run_rows_ = nullptr;
    if (next_frame_ >= end_frame_) return false;
    const BlockHandle& block = impl_->metadata().blocks[block_idx_];
    MOTIF_RETURN_IF_ERROR(impl_->DecodeBlock(block_idx_, &block_rows_));
    released_until_ = impl_->ReleasePages(released_until_, block.offset + block.bytes);
    const uint64_t block_end = block.first_frame + block.frame_count;
    run_first_ = next_frame_;
    run_count_ = std::min(block_end, end_frame_) - next_frame_;
    run_rows_ = block_rows_.data() +
                (next_frame_ - block.first_frame) * impl_->metadata().layout().stride();
    next_frame_ += run_count_;
    ++block_idx_;
    return true;
  }
  uint64_t first_frame() const override { return run_first_; }
  uint64_t frame_count() const override { return run_count_; }
  const float* rows() const override { return run_rows_; }

 private:
  const Impl* impl_;
  uint64_t next_frame_;
  uint64_t end_frame_;
  size_t block_idx_ = 0;
  uint64_t released_until_ = 0;  // file offset: pages before it were given back
  std::vector<float> block_rows_;
  uint64_t run_first_ = 0;
  uint64_t run_count_ = 0;
  const float* run_rows_ = nullptr;
};

namespace {

std::mutex older_version_mutex;
OlderVersionHandler& OlderVersionHandlerSlot() {
  static OlderVersionHandler handler;
  return handler;
}

}  // namespace

void SetOlderVersionHandler(OlderVersionHandler handler) {
  std::lock_guard<std::mutex> lock(older_version_mutex);
  OlderVersionHandlerSlot() = std::move(handler);
}

Result<std::unique_ptr<FrameFileReader>> FrameFileReader::Open(const std::string& path) {
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  MOTIF_ASSIGN_OR_RETURN(impl->file, MappedFile::Open(path));
  impl->data = impl->file->data();
  impl->size = impl->file->size();
  Result<frame_file::LoadedArchive> loaded = frame_file::LoadArchive(path, impl->data, impl->size);
  if (!loaded.ok()) return impl->file->ExplainRead(loaded.status());
  impl->archive = std::move(loaded).value();
  std::unique_ptr<FrameFileReader> reader(new FrameFileReader(std::move(impl)));
  if (!reader->impl_->archive.fallback_reason.empty()) {
    OlderVersionHandler handler;
    {
      std::lock_guard<std::mutex> lock(older_version_mutex);
      handler = OlderVersionHandlerSlot();
    }
    if (handler) MOTIF_RETURN_IF_ERROR(handler(path, reader->summary()));
  }
  return reader;
}

Result<std::unique_ptr<FrameFileReader>> FrameFileReader::OpenCommit(const std::string& path,
                                                                     uint64_t generation,
                                                                     uint64_t committed_length) {
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  MOTIF_ASSIGN_OR_RETURN(impl->file, MappedFile::Open(path));
  impl->data = impl->file->data();
  impl->size = impl->file->size();
  Result<frame_file::LoadedArchive> loaded =
      frame_file::LoadArchiveCommit(path, impl->data, impl->size, generation, committed_length);
  if (!loaded.ok()) return impl->file->ExplainRead(loaded.status());
  impl->archive = std::move(loaded).value();
  return std::unique_ptr<FrameFileReader>(new FrameFileReader(std::move(impl)));
}

Result<std::unique_ptr<FrameFileReader>> FrameFileReader::OpenVersion(
    const std::string& path, const FrameFileVersion& version) {
  if (version.newest()) return Open(path);
  return OpenCommit(path, version.generation, version.committed_bytes);
}

FrameFileReader::FrameFileReader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
FrameFileReader::~FrameFileReader() = default;

const std::string& FrameFileReader::path() const { return impl_->path; }
const Skeleton& FrameFileReader::skeleton() const { return impl_->metadata().skeleton; }
double FrameFileReader::fps() const { return impl_->metadata().fps; }
FrameLayout FrameFileReader::layout() const { return impl_->metadata().layout(); }
uint64_t FrameFileReader::frame_count() const { return impl_->metadata().frame_count; }
const std::vector<ClipInfo>& FrameFileReader::clips() const { return impl_->metadata().clips; }

FrameFileVersion FrameFileReader::version() const {
  return {impl_->archive.slot.generation, impl_->archive.slot.committed_length};
}

size_t FrameFileReader::ClipOfFrame(uint64_t frame_idx) const {
  const std::vector<ClipInfo>& clips = impl_->metadata().clips;
  MOTIF_CHECK(frame_idx < frame_count());
  auto after = std::upper_bound(
      clips.begin(), clips.end(), frame_idx,
      [](uint64_t frame, const ClipInfo& clip) { return frame < clip.first_frame; });
  return static_cast<size_t>(after - clips.begin()) - 1;
}

FrameFileSummary FrameFileReader::summary() const {
  const frame_file::LoadedArchive& archive = impl_->archive;
  FrameFileSummary summary;
  summary.file_bytes = archive.slot.committed_length;
  summary.block_count = archive.metadata.blocks.size();
  for (const BlockHandle& block : archive.metadata.blocks) summary.compressed_bytes += block.bytes;
  summary.block_frames = archive.metadata.block_frames;
  summary.generation = archive.slot.generation;
  summary.format_major = archive.header.format_major;
  summary.format_minor = archive.header.format_minor;
  summary.identity = archive.footer.metadata_checksum;
  summary.uncommitted_bytes = archive.file_bytes - archive.slot.committed_length;
  summary.fallback_reason = archive.fallback_reason;
  summary.damaged_slot_reason = archive.damaged_slot_reason;
  return summary;
}

Status FrameFileReader::ReadFrames(uint64_t first_frame, uint64_t frame_count,
                                   std::vector<float>* rows) const {
  const uint64_t total = this->frame_count();
  if (first_frame > total || frame_count > total - first_frame) {
    return Status::InvalidArgument(impl_->path + ": frames [" + std::to_string(first_frame) +
                                   ", +" + std::to_string(frame_count) +
                                   ") lie outside the archive's " + std::to_string(total) +
                                   " frames");
  }
  const size_t stride = layout().stride();
  rows->resize(frame_count * stride);
  if (frame_count == 0) return Status::Ok();
  thread_local std::vector<float> block_rows;
  const uint64_t end_frame = first_frame + frame_count;
  for (size_t block_idx = impl_->FindBlock(first_frame);
       block_idx < impl_->metadata().blocks.size(); ++block_idx) {
    const BlockHandle& block = impl_->metadata().blocks[block_idx];
    if (block.first_frame >= end_frame) break;
    MOTIF_RETURN_IF_ERROR(impl_->DecodeBlock(block_idx, &block_rows));
    const uint64_t copy_first = std::max(first_frame, block.first_frame);
    const uint64_t copy_end = std::min(end_frame, block.first_frame + block.frame_count);
    std::copy(block_rows.begin() + (copy_first - block.first_frame) * stride,
              block_rows.begin() + (copy_end - block.first_frame) * stride,
              rows->begin() + (copy_first - first_frame) * stride);
  }
  return Status::Ok();
}

std::unique_ptr<FrameStream> FrameFileReader::Stream(uint64_t first_frame,
                                                     uint64_t end_frame) const {
  end_frame = std::min(end_frame, frame_count());
  return std::make_unique<Impl::Stream>(impl_.get(), first_frame, end_frame);
}

Status FrameFileReader::Verify(const std::function<void(uint64_t, uint64_t)>& progress) const {
  if (!impl_->archive.fallback_reason.empty()) {
    return Status::Corruption(impl_->archive.fallback_reason + " (opened generation " +
                              std::to_string(impl_->archive.slot.generation) +
                              " from the other commit slot instead)");
  }
  if (!impl_->archive.damaged_slot_reason.empty()) {
    return Status::Corruption(impl_->archive.damaged_slot_reason +
                              " (its data is whole; the next import writes the other slot)");
  }
  std::vector<float> rows;
  const auto& blocks = impl_->metadata().blocks;
  const size_t block_count = blocks.size();
  // Blocks lie in file order: release each one's pages once checked, as a FrameStream does, so
  // verifying a large archive does not make it resident.
  uint64_t released_until = block_count > 0 ? blocks[0].offset : 0;
  for (size_t block_idx = 0; block_idx < block_count; ++block_idx) {
    MOTIF_RETURN_IF_ERROR(impl_->DecodeBlock(block_idx, &rows));
    released_until =
        impl_->ReleasePages(released_until, blocks[block_idx].offset + blocks[block_idx].bytes);
    if (progress) progress(block_idx + 1, block_count);
  }
  return Status::Ok();
}

}  // namespace motif
