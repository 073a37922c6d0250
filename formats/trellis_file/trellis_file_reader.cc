#include "formats/trellis_file/trellis_file_reader.h"

#include <algorithm>
#include <cstring>

#include "common/mapped_file.h"
#include "formats/format_checks/format_checks.h"
#include "formats/trellis_file/trellis_block_codec.h"
#include "formats/trellis_file/trellis_file_format.h"

namespace motif {

using trellis_file::BlockHandle;
using trellis_file::Hex;

namespace {

// One decoder per thread: const reader methods may run on many threads at once.
trellis_file::BlockDecoder& ThreadDecoder() {
  thread_local trellis_file::BlockDecoder decoder;
  return decoder;
}

}  // namespace

class TrellisFileReader::Impl {
 public:
  std::string path;
  std::unique_ptr<MappedFile> file;
  const uint8_t* data = nullptr;
  uint64_t size = 0;
  trellis_file::FileHeader header;
  uint64_t header_bytes = 0;
  trellis_file::Footer footer;
  std::vector<BlockHandle> blocks;

  Status Corrupt(const std::string& message) const {
    return Status::Corruption(path + ": " + message);
  }

  // Reader duties 3 to 9 of the spec, in order: identity, footer, header, index.
  Status Validate() {
    if (size == 0) return Corrupt("empty file");
    if (size < trellis_file::kFileMagic.size() ||
        std::memcmp(data, trellis_file::kFileMagic.data(), trellis_file::kFileMagic.size()) != 0) {
      return Corrupt("bad magic at offset 0x0: not a trellis file");
    }
    if (size >= 10 && trellis_file::LoadU16(data + 8) != trellis_file::kFormatMajor) {
      return Status::NotSupported(path + ": unsupported format major version " +
                                  std::to_string(trellis_file::LoadU16(data + 8)) +
                                  " (this reader knows " +
                                  std::to_string(trellis_file::kFormatMajor) + ")");
    }
    if (size < trellis_file::kMinHeaderBytes + trellis_file::kFooterBytes) {
      return Corrupt("file of " + std::to_string(size) +
                     " bytes is shorter than a header and a footer (truncated?)");
    }
    const uint64_t footer_offset = size - trellis_file::kFooterBytes;
    Status status = trellis_file::Footer::DecodeFrom(data + footer_offset, &footer);
    if (!status.ok()) return status.WithContext(path + ": footer at offset " + Hex(footer_offset));
    status = trellis_file::FileHeader::DecodeFrom(data, footer_offset, &header, &header_bytes);
    if (!status.ok()) return status.WithContext(path);
    if (trellis_file::LoadU64(data + header_bytes - 8) != footer.header_checksum) {
      return Corrupt("the header's checksum differs from the footer's copy");
    }
    // The index lies between the last block and the footer, exactly.
    if (!SectionEndsAt(footer.index_offset, footer.block_count, trellis_file::kBlockEntryBytes,
                       header_bytes, footer_offset)) {
      return Corrupt("block index at " + Hex(footer.index_offset) + " of " +
                     std::to_string(footer.block_count) + " entries does not end at the footer (" +
                     Hex(footer_offset) + ")");
    }
    const uint8_t* index = data + footer.index_offset;
    const uint64_t index_bytes = footer_offset - footer.index_offset;
    if (trellis_file::Checksum64(index, index_bytes) != footer.index_checksum) {
      return Corrupt("block index at " + Hex(footer.index_offset) + ": checksum mismatch");
    }
    return ValidateIndex(index);
  }

  // Blocks lie back to back from the header to the index, and their columns tile
  // [0, frame_count) in blocks of block_columns (the last one shorter).
  Status ValidateIndex(const uint8_t* index) {
    const TrellisParams& params = header.params;
    blocks.resize(footer.block_count);
    uint64_t offset = header_bytes;
    uint64_t next_column = 0;
    uint64_t neighbour_count = 0;
    for (uint64_t block_idx = 0; block_idx < footer.block_count; ++block_idx) {
      const BlockHandle block =
          BlockHandle::DecodeFrom(index + block_idx * trellis_file::kBlockEntryBytes);
      const std::string what = "block index entry " + std::to_string(block_idx) + ": ";
      if (block.offset != offset) {
        return Corrupt(what + "offset " + Hex(block.offset) + ", expected " + Hex(offset));
      }
      if (block.bytes < trellis_file::kBlockHeaderBytes + trellis_file::kBlockTrailerBytes ||
          block.bytes > footer.index_offset - offset) {
        return Corrupt(what + "block of " + std::to_string(block.bytes) + " bytes at " +
                       Hex(offset) + " does not fit before the index");
      }
      if (next_column >= params.frame_count || block.first_column != next_column ||
          block.column_count !=
              std::min<uint64_t>(header.block_columns, params.frame_count - next_column)) {
        return Corrupt(what + "columns [" + std::to_string(block.first_column) + ", +" +
                       std::to_string(block.column_count) + ") do not continue at column " +
                       std::to_string(next_column) + " in blocks of " +
                       std::to_string(header.block_columns) + " of " +
                       std::to_string(params.frame_count) + " columns");
      }
      if (block.neighbour_count > trellis_file::kMaxBlockNeighbours ||
          block.neighbour_count > uint64_t{block.column_count} * params.k_max) {
        return Corrupt(what + std::to_string(block.neighbour_count) + " neighbours in " +
                       std::to_string(block.column_count) + " columns exceed the limits");
      }
      blocks[block_idx] = block;
      offset += block.bytes;
      next_column += block.column_count;
      neighbour_count += block.neighbour_count;
    }
    if (offset != footer.index_offset || next_column != params.frame_count ||
        neighbour_count != footer.neighbour_count) {
      return Corrupt("the blocks end at " + Hex(offset) + " with " + std::to_string(next_column) +
                     " columns and " + std::to_string(neighbour_count) +
                     " neighbours; expected the index at " + Hex(footer.index_offset) + ", " +
                     std::to_string(params.frame_count) + " columns, " +
                     std::to_string(footer.neighbour_count) + " neighbours");
    }
    return Status::Ok();
  }

  Status DecodeBlock(uint64_t block_idx, TrellisBlock* block, bool decode_distances) const {
    const BlockHandle& handle = blocks[block_idx];
    trellis_file::BlockLimits limits;
    limits.frame_count = header.params.frame_count;
    limits.k_max = header.params.k_max;
    limits.eps = header.params.eps;
    Status status =
        ThreadDecoder().Decode(data + handle.offset, handle, limits, block, decode_distances);
    if (!status.ok()) {
      status = status.WithContext(path + ": block " + std::to_string(block_idx) + " at offset " +
                                  Hex(handle.offset));
    }
    return file->ExplainRead(status);  // zeros past a new end are the cut's fault, not the block's
  }

  // Gives the whole pages of file bytes [begin_offset, end_offset) back to the kernel and
  // returns the page-aligned end released.
  uint64_t ReleasePages(uint64_t begin_offset, uint64_t end_offset) const {
    return file->ReleasePages(begin_offset, end_offset);
  }
};

Result<std::unique_ptr<TrellisFileReader>> TrellisFileReader::Open(const std::string& path) {
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  MOTIF_ASSIGN_OR_RETURN(impl->file, MappedFile::Open(path));
  impl->data = impl->file->data();
  impl->size = impl->file->size();
  MOTIF_RETURN_IF_ERROR(impl->file->ExplainRead(impl->Validate()));
  return std::unique_ptr<TrellisFileReader>(new TrellisFileReader(std::move(impl)));
}

TrellisFileReader::TrellisFileReader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
TrellisFileReader::~TrellisFileReader() = default;

const TrellisParams& TrellisFileReader::params() const { return impl_->header.params; }
uint64_t TrellisFileReader::column_count() const { return impl_->header.params.frame_count; }
uint32_t TrellisFileReader::block_columns() const { return impl_->header.block_columns; }
uint64_t TrellisFileReader::block_count() const { return impl_->blocks.size(); }
uint64_t TrellisFileReader::neighbour_count() const { return impl_->footer.neighbour_count; }
uint64_t TrellisFileReader::file_bytes() const { return impl_->size; }
const std::string& TrellisFileReader::path() const { return impl_->path; }
uint16_t TrellisFileReader::format_minor() const { return impl_->footer.format_minor; }
uint64_t TrellisFileReader::identity() const {
  return trellis_file::LoadU64(impl_->data + impl_->size - 8);  // the footer checksum
}

Status TrellisFileReader::ReadBlock(uint64_t block_idx, TrellisBlock* block,
                                    bool decode_distances) const {
  if (block_idx >= block_count()) {
    return Status::InvalidArgument(impl_->path + ": block " + std::to_string(block_idx) + " of " +
                                   std::to_string(block_count()));
  }
  return impl_->DecodeBlock(block_idx, block, decode_distances);
}

Status TrellisFileReader::ReadEncodedBlock(uint64_t block_idx, const uint8_t** bytes,
                                           uint64_t* size) const {
  if (block_idx >= block_count()) {
    return Status::InvalidArgument(impl_->path + ": block " + std::to_string(block_idx) + " of " +
                                   std::to_string(block_count()));
  }
  const BlockHandle& handle = impl_->blocks[block_idx];
  const uint8_t* data = impl_->data + handle.offset;
  const uint64_t body = handle.bytes - trellis_file::kBlockTrailerBytes;
  if (trellis_file::LoadU64(data + body) != handle.checksum ||
      trellis_file::Checksum64(data, body) != handle.checksum) {
    return impl_->file->ExplainRead(
        Status::Corruption(impl_->path + ": block " + std::to_string(block_idx) + " at offset " +
                           Hex(handle.offset) + ": checksum mismatch"));
  }
  *bytes = data;
  *size = handle.bytes;
  return Status::Ok();
}

Status TrellisFileReader::ReadColumns(uint64_t first_column, uint64_t count,
                                      std::vector<std::vector<Neighbour>>* columns) const {
  const uint64_t total = column_count();
  if (first_column > total || count > total - first_column) {
    return Status::InvalidArgument(impl_->path + ": columns [" + std::to_string(first_column) +
                                   ", +" + std::to_string(count) + ") lie outside the " +
                                   std::to_string(total) + " columns");
  }
  columns->resize(count);
  if (count == 0) return Status::Ok();
  thread_local TrellisBlock block;
  const uint64_t end_column = first_column + count;
  for (uint64_t block_idx = first_column / block_columns();
       block_idx < block_count() && impl_->blocks[block_idx].first_column < end_column;
       ++block_idx) {
    MOTIF_RETURN_IF_ERROR(impl_->DecodeBlock(block_idx, &block, /*decode_distances=*/true));
    const uint64_t copy_first = std::max(first_column, block.first_column);
    const uint64_t copy_end = std::min(end_column, block.first_column + block.column_count);
    for (uint64_t column_idx = copy_first; column_idx < copy_end; ++column_idx) {
      const uint64_t in_block = column_idx - block.first_column;
      (*columns)[column_idx - first_column].assign(
          block.neighbours.begin() + block.offsets[in_block],
          block.neighbours.begin() + block.offsets[in_block + 1]);
    }
  }
  return Status::Ok();
}

Status TrellisFileReader::ReleaseBlocks(uint64_t first_block, uint64_t end_block) const {
  if (first_block > end_block || end_block > block_count()) {
    return Status::InvalidArgument(impl_->path + ": release blocks [" +
                                   std::to_string(first_block) + ", " + std::to_string(end_block) +
                                   ") of " + std::to_string(block_count()));
  }
  if (first_block == end_block) return Status::Ok();
  const BlockHandle& last = impl_->blocks[end_block - 1];
  impl_->ReleasePages(impl_->blocks[first_block].offset, last.offset + last.bytes);
  return Status::Ok();
}

Status TrellisFileReader::Verify() const {
  TrellisBlock block;
  const std::vector<BlockHandle>& blocks = impl_->blocks;
  uint64_t released_until = blocks.empty() ? 0 : blocks[0].offset;
  for (uint64_t block_idx = 0; block_idx < blocks.size(); ++block_idx) {
    MOTIF_RETURN_IF_ERROR(impl_->DecodeBlock(block_idx, &block, /*decode_distances=*/true));
    released_until =
        impl_->ReleasePages(released_until, blocks[block_idx].offset + blocks[block_idx].bytes);
  }
  return Status::Ok();
}

}  // namespace motif
