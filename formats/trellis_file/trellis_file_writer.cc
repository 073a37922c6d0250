#include "formats/trellis_file/trellis_file_writer.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <boost/interprocess/file_mapping.hpp>
#include <boost/interprocess/mapped_region.hpp>

#include "formats/trellis_file/trellis_block_codec.h"
#include "formats/trellis_file/trellis_file_format.h"

#include "common/file_lock.h"

namespace motif {

using trellis_file::BlockHandle;
using trellis_file::BlockHeader;

namespace {

// What a resume scan found in a partial file.
struct ScanResult {
  bool header_matches = false;      // else the file is stale: start over
  std::vector<BlockHandle> blocks;  // the complete, valid blocks, in order
  uint64_t valid_end = 0;           // where the first invalid byte (or the end) is
};

// Scans a partial file's bytes: the header must be exactly `expected_header`; then blocks are
// taken in order while each is complete, checksums, and holds the next columns.
ScanResult ScanPartial(const uint8_t* data, uint64_t size, const std::string& expected_header,
                       const TrellisParams& params, uint32_t block_columns) {
  ScanResult result;
  if (size < expected_header.size() ||
      std::memcmp(data, expected_header.data(), expected_header.size()) != 0) {
    return result;
  }
  result.header_matches = true;
  uint64_t offset = expected_header.size();
  uint64_t next_column = 0;
  while (next_column < params.frame_count) {
    BlockHeader header;
    uint64_t checksum = 0;
    if (!trellis_file::CheckBlockFraming(data + offset, size - offset, &header, &checksum).ok()) {
      break;
    }
    const uint64_t expected_columns =
        std::min<uint64_t>(block_columns, params.frame_count - next_column);
    if (header.first_column != next_column || header.column_count != expected_columns ||
        header.neighbour_count > uint64_t{header.column_count} * params.k_max ||
        header.neighbour_count > trellis_file::kMaxBlockNeighbours) {
      break;
    }
    BlockHandle handle;
    handle.offset = offset;
    handle.bytes = header.block_bytes();
    handle.first_column = header.first_column;
    handle.column_count = header.column_count;
    handle.neighbour_count = header.neighbour_count;
    handle.checksum = checksum;
    result.blocks.push_back(handle);
    offset += handle.bytes;
    next_column += handle.column_count;
  }
  result.valid_end = offset;
  return result;
}

}  // namespace

class TrellisFileWriter::Impl {
 public:
  Impl(const std::string& path, const TrellisParams& params,
       const TrellisFileWriterOptions& options)
      : path_(path),
        partial_path_(PartialPath(path)),
        params_(params),
        options_(options),
        fs_(options.file_system),
        encoder_(options.zstd_level) {
    trellis_file::FileHeader header;
    header.block_columns = options.block_columns;
    header.params = params;
    header.EncodeTo(&header_bytes_);
  }
  ~Impl() { Close(); }

  // Opens (or creates) the partial file, locks it, and resumes or starts over.
  Status Open() {
    std::error_code error;
    const bool exists = std::filesystem::exists(partial_path_, error);
    MOTIF_ASSIGN_OR_RETURN(
        file_, fs_->OpenWritable(partial_path_,
                                 exists ? OpenMode::kExisting : OpenMode::kCreateExclusive));
    MOTIF_RETURN_IF_ERROR(
        lock_.Acquire(partial_path_, "locked: another writer is building this trellis"));
    if (exists) {
      MOTIF_ASSIGN_OR_RETURN(const uint64_t size, file_->Size());
      MOTIF_ASSIGN_OR_RETURN(ScanResult scan, Scan(size));
      if (scan.header_matches) {
        for (const BlockHandle& block : scan.blocks) {
          next_column_ += block.column_count;
          neighbour_count_ += block.neighbour_count;
        }
        index_ = std::move(scan.blocks);
        write_offset_ = scan.valid_end;
        if (scan.valid_end < size) {
          // A torn or damaged tail (or the index and footer of an interrupted Finish): drop it.
          MOTIF_RETURN_IF_ERROR(file_->Truncate(scan.valid_end));
          MOTIF_RETURN_IF_ERROR(file_->Sync());
        }
        return Status::Ok();
      }
      MOTIF_RETURN_IF_ERROR(file_->Truncate(0));  // stale: other params, block size or version
    }
    MOTIF_RETURN_IF_ERROR(file_->WriteAt(0, header_bytes_.data(), header_bytes_.size()));
    MOTIF_RETURN_IF_ERROR(file_->Sync());
    write_offset_ = header_bytes_.size();
    return fs_->SyncParentDir(partial_path_);
  }

  uint64_t next_column() const { return next_column_; }
  uint32_t block_columns() const { return options_.block_columns; }

  Status AppendBlock(const std::vector<std::vector<Neighbour>>& columns) {
    MOTIF_RETURN_IF_ERROR(CheckUsable());
    MOTIF_RETURN_IF_ERROR(CheckColumns(columns));
    BlockHandle handle;
    Status status = encoder_.Encode(next_column_, columns, params_.eps, &block_bytes_, &handle);
    if (!status.ok()) return Fail(status);
    return WriteBlock(reinterpret_cast<const uint8_t*>(block_bytes_.data()), handle);
  }

  // Writes a block of `handle.bytes` bytes at the end and syncs it; records it in the index.
  Status WriteBlock(const uint8_t* bytes, BlockHandle handle) {
    Status status = file_->WriteAt(write_offset_, bytes, handle.bytes);
    if (status.ok() && options_.sync_each_block) status = file_->Sync();
    if (!status.ok()) return Fail(status);
    handle.offset = write_offset_;
    index_.push_back(handle);
    write_offset_ += handle.bytes;
    next_column_ += handle.column_count;
    neighbour_count_ += handle.neighbour_count;
    return Status::Ok();
  }

  Status AppendEncodedBlock(const uint8_t* bytes, uint64_t size) {
    MOTIF_RETURN_IF_ERROR(CheckUsable());
    BlockHeader header;
    uint64_t checksum = 0;
    Status framing = trellis_file::CheckBlockFraming(bytes, size, &header, &checksum);
    if (!framing.ok()) return Invalid("encoded block: " + framing.message());
    if (header.block_bytes() != size) {
      return Invalid("encoded block of " + std::to_string(size) + " bytes holds a block of " +
                     std::to_string(header.block_bytes()));
    }
    MOTIF_RETURN_IF_ERROR(CheckBlockShape(header.first_column, header.column_count));
    if (header.neighbour_count > uint64_t{header.column_count} * params_.k_max ||
        header.neighbour_count > trellis_file::kMaxBlockNeighbours) {
      return Invalid("encoded block at column " + std::to_string(header.first_column) + " has " +
                     std::to_string(header.neighbour_count) + " neighbours, more than k_max " +
                     std::to_string(params_.k_max) + " a column");
    }
    BlockHandle handle;
    handle.bytes = size;
    handle.first_column = header.first_column;
    handle.column_count = header.column_count;
    handle.neighbour_count = header.neighbour_count;
    handle.checksum = checksum;
    return WriteBlock(bytes, handle);
  }

  Status Finish() {
    MOTIF_RETURN_IF_ERROR(CheckUsable());
    if (next_column_ != params_.frame_count) {
      return Invalid("Finish after " + std::to_string(next_column_) + " of " +
                     std::to_string(params_.frame_count) + " columns");
    }
    std::string tail;
    for (const BlockHandle& block : index_) block.EncodeTo(&tail);
    trellis_file::Footer footer;
    footer.index_offset = write_offset_;
    footer.block_count = index_.size();
    footer.neighbour_count = neighbour_count_;
    footer.index_checksum = trellis_file::Checksum64(tail.data(), tail.size());
    footer.header_checksum = trellis_file::LoadU64(
        reinterpret_cast<const uint8_t*>(header_bytes_.data()) + header_bytes_.size() - 8);
    footer.EncodeTo(&tail);
    Status status = file_->WriteAt(write_offset_, tail.data(), tail.size());
    if (status.ok()) status = file_->Sync();
    if (status.ok()) status = file_->Close();
    if (status.ok()) status = fs_->Rename(partial_path_, path_);
    // Renamed: the trellis is in place (a failed directory sync only risks its durability).
    if (status.ok()) status = fs_->SyncParentDir(path_);
    if (!status.ok()) return Fail(status);
    closed_ = true;
    Close();
    return Status::Ok();
  }

 private:
  Status Invalid(const std::string& message) const {
    return Status::InvalidArgument(partial_path_ + ": " + message);
  }

  Status CheckUsable() const {
    if (!failure_.ok()) return failure_;
    if (closed_) return Invalid("the writer is closed (finished)");
    return Status::Ok();
  }

  // A block of `column_count` columns from `first_column` is the one expected next.
  Status CheckBlockShape(uint64_t first_column, uint64_t column_count) const {
    if (next_column_ >= params_.frame_count) {
      return Invalid("all " + std::to_string(params_.frame_count) +
                     " columns are written: call Finish");
    }
    const uint64_t expected =
        std::min<uint64_t>(options_.block_columns, params_.frame_count - next_column_);
    if (first_column != next_column_ || column_count != expected) {
      return Invalid("block at column " + std::to_string(first_column) + " has " +
                     std::to_string(column_count) + " columns, expected " +
                     std::to_string(expected) + " from column " + std::to_string(next_column_));
    }
    return Status::Ok();
  }

  // Everything AppendBlock promises to reject, checked before anything is written.
  Status CheckColumns(const std::vector<std::vector<Neighbour>>& columns) const {
    MOTIF_RETURN_IF_ERROR(CheckBlockShape(next_column_, columns.size()));
    uint64_t neighbour_count = 0;
    for (size_t column_idx = 0; column_idx < columns.size(); ++column_idx) {
      const std::vector<Neighbour>& column = columns[column_idx];
      const auto where = [&] { return "column " + std::to_string(next_column_ + column_idx); };
      if (column.size() > params_.k_max) {
        return Invalid(where() + " has " + std::to_string(column.size()) +
                       " neighbours, more than k_max " + std::to_string(params_.k_max));
      }
      neighbour_count += column.size();
      for (size_t entry_idx = 0; entry_idx < column.size(); ++entry_idx) {
        const Neighbour& neighbour = column[entry_idx];
        if (neighbour.frame >= params_.frame_count) {
          return Invalid(where() + ": frame " + std::to_string(neighbour.frame) +
                         " is outside the archive's " + std::to_string(params_.frame_count));
        }
        if (entry_idx > 0 && neighbour.frame <= column[entry_idx - 1].frame) {
          return Invalid(where() + ": frames are not strictly increasing at entry " +
                         std::to_string(entry_idx));
        }
        if (!(neighbour.distance >= 0 && neighbour.distance <= params_.eps)) {
          return Invalid(where() + ": distance " + std::to_string(neighbour.distance) +
                         " of frame " + std::to_string(neighbour.frame) +
                         " is not in [0, eps = " + std::to_string(params_.eps) + "]");
        }
      }
    }
    if (neighbour_count > trellis_file::kMaxBlockNeighbours) {
      return Invalid("block at column " + std::to_string(next_column_) + " has " +
                     std::to_string(neighbour_count) +
                     " neighbours, more than 2^28: use fewer block_columns");
    }
    return Status::Ok();
  }

  // Maps the partial file read-only just long enough to scan it.
  Result<ScanResult> Scan(uint64_t size) const {
    if (size == 0) return ScanResult();
    try {
      namespace bip = boost::interprocess;
      bip::file_mapping mapping(partial_path_.c_str(), bip::read_only);
      bip::mapped_region region(mapping, bip::read_only, 0, size);
      return ScanPartial(static_cast<const uint8_t*>(region.get_address()), size, header_bytes_,
                         params_, options_.block_columns);
    } catch (const std::exception& exception) {
      return Status::IOError(partial_path_ + ": cannot map to resume: " + exception.what());
    }
  }

  // Records a failure (every later call returns it) and lets go of the file: what is durable
  // stays for a resume.
  Status Fail(const Status& status) {
    failure_ = status;
    Close();
    return status;
  }

  // Finish closes the file itself and checks it; here it is a failure or an abandoned build, and
  // what was synced stays for a resume: a close error has nothing to add.
  void Close() {
    if (file_) (void)file_->Close();
    file_.reset();
    lock_.Release();
  }

  std::string path_;
  std::string partial_path_;
  TrellisParams params_;
  TrellisFileWriterOptions options_;
  FileSystem* fs_;
  std::string header_bytes_;
  std::unique_ptr<WritableFile> file_;
  ExclusiveFileLock lock_;
  trellis_file::BlockEncoder encoder_;
  std::string block_bytes_;
  std::vector<BlockHandle> index_;  // the blocks written so far
  uint64_t write_offset_ = 0;       // where the next block goes
  uint64_t next_column_ = 0;
  uint64_t neighbour_count_ = 0;
  Status failure_;
  bool closed_ = false;
};

std::string TrellisFileWriter::PartialPath(const std::string& path) { return path + ".partial"; }

Result<std::unique_ptr<TrellisFileWriter>> TrellisFileWriter::OpenOrResume(
    const std::string& path, const TrellisParams& params, const TrellisFileWriterOptions& options) {
  const std::string problem = trellis_file::ParamsProblem(params);
  if (!problem.empty()) return Status::InvalidArgument(path + ": trellis params: " + problem);
  if (params.search_params.size() > trellis_file::kMaxSearchParamsBytes) {
    return Status::InvalidArgument(path + ": search_params of " +
                                   std::to_string(params.search_params.size()) +
                                   " bytes, more than 64 KiB");
  }
  if (options.block_columns == 0 || options.block_columns > trellis_file::kMaxBlockColumns) {
    return Status::InvalidArgument(path + ": block_columns " +
                                   std::to_string(options.block_columns) + " is not in [1, 2^20]");
  }
  if (!trellis_file::IsValidZstdLevel(options.zstd_level)) {
    return Status::InvalidArgument(path + ": zstd level " + std::to_string(options.zstd_level) +
                                   " is out of range");
  }
  if (options.file_system == nullptr) {
    return Status::InvalidArgument(path + ": no file system given");
  }
  auto impl = std::make_unique<Impl>(path, params, options);
  MOTIF_RETURN_IF_ERROR(impl->Open());
  return std::unique_ptr<TrellisFileWriter>(new TrellisFileWriter(std::move(impl)));
}

TrellisFileWriter::TrellisFileWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
TrellisFileWriter::~TrellisFileWriter() = default;

uint64_t TrellisFileWriter::next_column() const { return impl_->next_column(); }
uint32_t TrellisFileWriter::block_columns() const { return impl_->block_columns(); }

Status TrellisFileWriter::AppendBlock(const std::vector<std::vector<Neighbour>>& columns) {
  return impl_->AppendBlock(columns);
}

Status TrellisFileWriter::AppendEncodedBlock(const uint8_t* bytes, uint64_t size) {
  return impl_->AppendEncodedBlock(bytes, size);
}

Status TrellisFileWriter::Finish() { return impl_->Finish(); }

}  // namespace motif
