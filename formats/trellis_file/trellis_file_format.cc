#include "formats/trellis_file/trellis_file_format.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "formats/format_checks/format_checks.h"

namespace motif {

// Floats compare by their bits: the params are stored bit for bit, and two builds are
// interchangeable only if the stored bytes are the same.
bool TrellisParams::operator==(const TrellisParams& other) const {
  return frame_count == other.frame_count && archive_identity == other.archive_identity &&
         std::bit_cast<uint32_t>(eps) == std::bit_cast<uint32_t>(other.eps) &&
         std::bit_cast<uint32_t>(mu) == std::bit_cast<uint32_t>(other.mu) &&
         std::bit_cast<uint32_t>(sigma) == std::bit_cast<uint32_t>(other.sigma) &&
         k_max == other.k_max && exclusion_frames == other.exclusion_frames &&
         search_mode == other.search_mode && seed == other.seed &&
         weights_hash == other.weights_hash && search_params == other.search_params;
}

namespace trellis_file {

// Params, 60 bytes + search_params:
//   0 frame_count u64 | 8 archive_identity u64 | 16 eps f32 | 20 mu f32 | 24 sigma f32
//   28 k_max u32 | 32 exclusion_frames u32 | 36 search_mode u32 | 40 seed u64
//   48 weights_hash u64 | 56 search_params: length u32, then the bytes
void EncodeParams(const TrellisParams& params, std::string* out) {
  PutU64(out, params.frame_count);
  PutU64(out, params.archive_identity);
  PutF32(out, params.eps);
  PutF32(out, params.mu);
  PutF32(out, params.sigma);
  PutU32(out, params.k_max);
  PutU32(out, params.exclusion_frames);
  PutU32(out, params.search_mode);
  PutU64(out, params.seed);
  PutU64(out, params.weights_hash);
  PutU32(out, static_cast<uint32_t>(params.search_params.size()));
  out->append(params.search_params);
}

std::string ParamsProblem(const TrellisParams& params) {
  if (!std::isfinite(params.eps) || !(params.eps > 0)) {
    return "eps " + std::to_string(params.eps) + " is not finite and > 0";
  }
  if (params.frame_count > kMaxFrameCount) {
    return "frame_count " + std::to_string(params.frame_count) +
           " exceeds 2^32 (frame ids are 32-bit)";
  }
  if (params.k_max == 0) return "k_max is 0";
  return "";
}

Status DecodeParams(const uint8_t* bytes, size_t size, TrellisParams* params) {
  if (size < kParamsFixedBytes) {
    return Status::Corruption("params of " + std::to_string(size) + " bytes, at least " +
                              std::to_string(kParamsFixedBytes) + " expected");
  }
  params->frame_count = LoadU64(bytes);
  params->archive_identity = LoadU64(bytes + 8);
  params->eps = std::bit_cast<float>(LoadU32(bytes + 16));
  params->mu = std::bit_cast<float>(LoadU32(bytes + 20));
  params->sigma = std::bit_cast<float>(LoadU32(bytes + 24));
  params->k_max = LoadU32(bytes + 28);
  params->exclusion_frames = LoadU32(bytes + 32);
  params->search_mode = LoadU32(bytes + 36);
  params->seed = LoadU64(bytes + 40);
  params->weights_hash = LoadU64(bytes + 48);
  const uint32_t text_bytes = LoadU32(bytes + 56);
  if (text_bytes > size - kParamsFixedBytes) {
    return Status::Corruption("params: search_params of " + std::to_string(text_bytes) +
                              " bytes runs past the params");
  }
  params->search_params.assign(reinterpret_cast<const char*>(bytes + kParamsFixedBytes),
                               text_bytes);
  const std::string problem = ParamsProblem(*params);
  if (!problem.empty()) return Status::Corruption("params: " + problem);
  return Status::Ok();
}

// File header, 32 + params_bytes + 8 bytes:
//   0 magic[8] | 8 format_major u16 | 10 format_minor u16 | 12 header_bytes u32
//   16 block_columns u32 | 20 params_bytes u32 | 24 reserved u64 (0)
//   32 params (params_bytes) | header_bytes - 8: checksum u64 = Checksum64([0, header_bytes - 8))
void FileHeader::EncodeTo(std::string* out) const {
  std::string encoded_params;
  EncodeParams(params, &encoded_params);
  std::string header(kFileMagic.begin(), kFileMagic.end());
  PutU16(&header, format_major);
  PutU16(&header, format_minor);
  PutU32(&header, static_cast<uint32_t>(kHeaderFixedBytes + encoded_params.size() + 8));
  PutU32(&header, block_columns);
  PutU32(&header, static_cast<uint32_t>(encoded_params.size()));
  PutU64(&header, 0);
  header += encoded_params;
  PutU64(&header, Checksum64(header.data(), header.size()));
  out->append(header);
}

Status FileHeader::DecodeFrom(const uint8_t* bytes, size_t size, FileHeader* header,
                              uint64_t* header_bytes) {
  if (size < kFileMagic.size() || std::memcmp(bytes, kFileMagic.data(), kFileMagic.size()) != 0) {
    return Status::Corruption("bad magic at offset 0x0: not a trellis file");
  }
  if (size < kMinHeaderBytes) {
    return Status::Corruption("file is " + std::to_string(size) +
                              " bytes, shorter than the smallest header (" +
                              std::to_string(kMinHeaderBytes) + ")");
  }
  // The magic and the major version at offset 8 are the stable part of every version: check the
  // version before anything whose layout a future major may change.
  header->format_major = LoadU16(bytes + 8);
  header->format_minor = LoadU16(bytes + 10);
  if (header->format_major != kFormatMajor) {
    return Status::NotSupported("unsupported format major version " +
                                std::to_string(header->format_major) + " (this reader knows " +
                                std::to_string(kFormatMajor) + ")");
  }
  const uint32_t declared_bytes = LoadU32(bytes + 12);
  const uint32_t params_bytes = LoadU32(bytes + 20);
  if (declared_bytes > size || params_bytes > kMaxParamsBytes ||
      declared_bytes != kHeaderFixedBytes + uint64_t{params_bytes} + 8) {
    return Status::Corruption("header size " + std::to_string(declared_bytes) +
                              " disagrees with its params size " + std::to_string(params_bytes) +
                              " or the file size " + std::to_string(size));
  }
  if (LoadU64(bytes + declared_bytes - 8) != Checksum64(bytes, declared_bytes - 8)) {
    return Status::Corruption("header at offset 0x0: checksum mismatch");
  }
  if (LoadU64(bytes + 24) != 0) {
    return Status::Corruption("header reserved field at offset 0x18 is not zero");
  }
  header->block_columns = LoadU32(bytes + 16);
  if (header->block_columns == 0 || header->block_columns > kMaxBlockColumns) {
    return Status::Corruption("header: block_columns " + std::to_string(header->block_columns) +
                              " is not in [1, 2^20]");
  }
  MOTIF_RETURN_IF_ERROR(DecodeParams(bytes + kHeaderFixedBytes, params_bytes, &header->params));
  *header_bytes = declared_bytes;
  return Status::Ok();
}

// Block header, 40 bytes:
//   0 magic "MTBK" | 4 column_count u32 | 8 first_column u64 | 16 neighbour_count u32
//   20 ids_raw_bytes u32 | 24 ids_bytes u32 | 28 distances_bytes u32 | 32 reserved u64 (0)
void BlockHeader::EncodeTo(std::string* out) const {
  out->append(kBlockMagic.begin(), kBlockMagic.end());
  PutU32(out, column_count);
  PutU64(out, first_column);
  PutU32(out, neighbour_count);
  PutU32(out, ids_raw_bytes);
  PutU32(out, ids_bytes);
  PutU32(out, distances_bytes);
  PutU64(out, 0);
}

Status BlockHeader::DecodeFrom(const uint8_t* bytes, BlockHeader* header) {
  if (std::memcmp(bytes, kBlockMagic.data(), kBlockMagic.size()) != 0) {
    return Status::Corruption("bad block magic");
  }
  header->column_count = LoadU32(bytes + 4);
  header->first_column = LoadU64(bytes + 8);
  header->neighbour_count = LoadU32(bytes + 16);
  header->ids_raw_bytes = LoadU32(bytes + 20);
  header->ids_bytes = LoadU32(bytes + 24);
  header->distances_bytes = LoadU32(bytes + 28);
  if (LoadU64(bytes + 32) != 0) return Status::Corruption("block reserved field is not zero");
  return Status::Ok();
}

// Block index entry, 40 bytes:
//   0 offset u64 | 8 bytes u64 | 16 first_column u64 | 24 column_count u32
//   28 neighbour_count u32 | 32 checksum u64
void BlockHandle::EncodeTo(std::string* out) const {
  PutU64(out, offset);
  PutU64(out, bytes);
  PutU64(out, first_column);
  PutU32(out, column_count);
  PutU32(out, neighbour_count);
  PutU64(out, checksum);
}

BlockHandle BlockHandle::DecodeFrom(const uint8_t* bytes) {
  BlockHandle handle;
  handle.offset = LoadU64(bytes);
  handle.bytes = LoadU64(bytes + 8);
  handle.first_column = LoadU64(bytes + 16);
  handle.column_count = LoadU32(bytes + 24);
  handle.neighbour_count = LoadU32(bytes + 28);
  handle.checksum = LoadU64(bytes + 32);
  return handle;
}

// Footer, 64 bytes:
//   0 magic[8] | 8 format_major u16 | 10 format_minor u16 | 12 footer_bytes u32 (64)
//   16 index_offset u64 | 24 block_count u64 | 32 neighbour_count u64 | 40 index_checksum u64
//   48 header_checksum u64 | 56 footer_checksum u64 = Checksum64([0, 56))
void Footer::EncodeTo(std::string* out) const {
  std::string footer(kFooterMagic.begin(), kFooterMagic.end());
  PutU16(&footer, format_major);
  PutU16(&footer, format_minor);
  PutU32(&footer, static_cast<uint32_t>(kFooterBytes));
  PutU64(&footer, index_offset);
  PutU64(&footer, block_count);
  PutU64(&footer, neighbour_count);
  PutU64(&footer, index_checksum);
  PutU64(&footer, header_checksum);
  PutU64(&footer, Checksum64(footer.data(), footer.size()));
  out->append(footer);
}

Status Footer::DecodeFrom(const uint8_t* bytes, Footer* footer) {
  constexpr FooterFrame kFrame{kFooterMagic, kFormatMajor, kFooterBytes,
                               "bad footer magic (an unfinished or truncated trellis file?)"};
  MOTIF_RETURN_IF_ERROR(
      CheckFooterFrame(bytes, kFrame, &footer->format_major, &footer->format_minor));
  footer->index_offset = LoadU64(bytes + 16);
  footer->block_count = LoadU64(bytes + 24);
  footer->neighbour_count = LoadU64(bytes + 32);
  footer->index_checksum = LoadU64(bytes + 40);
  footer->header_checksum = LoadU64(bytes + 48);
  return Status::Ok();
}

}  // namespace trellis_file
}  // namespace motif
