#include "formats/frame_file/frame_file_format.h"

#include <bit>
#include <cstdio>
#include <cstring>

#include "formats/format_checks/format_checks.h"

namespace motif::frame_file {
bool ByteReader::GetU8(uint8_t* value) {
  if (remaining() < 1) return false;
  *value = data_[pos_++];
  return true;
}

bool ByteReader::GetU16(uint16_t* value) {
  if (remaining() < 2) return false;
  *value = LoadU16(data_ + pos_);
  pos_ += 2;
  return true;
}

bool ByteReader::GetU32(uint32_t* value) {
  if (remaining() < 4) return false;
  *value = LoadU32(data_ + pos_);
  pos_ += 4;
  return true;
}

bool ByteReader::GetI32(int32_t* value) {
  uint32_t bits = 0;
  if (!GetU32(&bits)) return false;
  *value = static_cast<int32_t>(bits);
  return true;
}

bool ByteReader::GetU64(uint64_t* value) {
  if (remaining() < 8) return false;
  *value = LoadU64(data_ + pos_);
  pos_ += 8;
  return true;
}

bool ByteReader::GetF32(float* value) {
  uint32_t bits = 0;
  if (!GetU32(&bits)) return false;
  *value = std::bit_cast<float>(bits);
  return true;
}

bool ByteReader::GetF64(double* value) {
  uint64_t bits = 0;
  if (!GetU64(&bits)) return false;
  *value = std::bit_cast<double>(bits);
  return true;
}

bool ByteReader::GetString(std::string* value) {
  uint32_t length = 0;
  const size_t start = pos_;
  if (!GetU32(&length)) return false;
  if (remaining() < length) {
    pos_ = start;
    return false;
  }
  value->assign(reinterpret_cast<const char*>(data_ + pos_), length);
  pos_ += length;
  return true;
}

bool ByteReader::GetBytes(size_t size, const uint8_t** bytes) {
  if (remaining() < size) return false;
  *bytes = data_ + pos_;
  pos_ += size;
  return true;
}

bool ByteReader::Skip(size_t size) {
  if (remaining() < size) return false;
  pos_ += size;
  return true;
}

// Commit slot, 40 bytes:
//   0 generation u64 | 8 footer_offset u64 | 16 committed_length u64 | 24 reserved u64 (0)
//   32 checksum u64 = Checksum64(bytes [0, 32))
void CommitSlot::EncodeTo(std::string* out) const {
  std::string slot;
  PutU64(&slot, generation);
  PutU64(&slot, footer_offset);
  PutU64(&slot, committed_length);
  PutU64(&slot, 0);
  PutU64(&slot, Checksum64(slot.data(), slot.size()));
  out->append(slot);
}

Status CommitSlot::DecodeFrom(const uint8_t* bytes, CommitSlot* slot, bool* is_empty) {
  *slot = CommitSlot();
  *is_empty = true;
  for (size_t byte_idx = 0; byte_idx < kSlotBytes; ++byte_idx) {
    if (bytes[byte_idx] != 0) *is_empty = false;
  }
  if (*is_empty) return Status::Ok();
  if (LoadU64(bytes + 32) != Checksum64(bytes, 32)) {
    return Status::Corruption("checksum mismatch");
  }
  if (LoadU64(bytes + 24) != 0) return Status::Corruption("reserved field is not zero");
  slot->generation = LoadU64(bytes);
  slot->footer_offset = LoadU64(bytes + 8);
  slot->committed_length = LoadU64(bytes + 16);
  if (slot->generation == 0) return Status::Corruption("generation 0 in a written slot");
  return Status::Ok();
}

// File header, 128 bytes:
//   0 magic[8] | 8 format_major u16 | 10 format_minor u16 | 12 header_bytes u32 (128)
//   16 reserved u64 x3 (0) | 40 header_checksum u64 = Checksum64(bytes [0, 40))
//   48 slot 0 (40 B) | 88 slot 1 (40 B)
void FileHeader::EncodeTo(std::string* out) const {
  std::string fixed(kFileMagic.begin(), kFileMagic.end());
  PutU16(&fixed, format_major);
  PutU16(&fixed, format_minor);
  PutU32(&fixed, static_cast<uint32_t>(kHeaderBytes));
  PutU64(&fixed, 0);
  PutU64(&fixed, 0);
  PutU64(&fixed, 0);
  PutU64(&fixed, Checksum64(fixed.data(), fixed.size()));
  out->append(fixed);
  for (const CommitSlot& slot : slots) {
    if (slot.empty()) {
      out->append(kSlotBytes, '\0');
    } else {
      slot.EncodeTo(out);
    }
  }
}

Status FileHeader::DecodeFixedFrom(const uint8_t* bytes, size_t size, FileHeader* header) {
  if (size < kHeaderBytes) {
    return Status::Corruption("file is " + std::to_string(size) + " bytes, shorter than the " +
                              std::to_string(kHeaderBytes) + "-byte header");
  }
  if (std::memcmp(bytes, kFileMagic.data(), kFileMagic.size()) != 0) {
    return Status::Corruption("bad magic at offset 0x0: not a motion archive (.mfs)");
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
  if (LoadU64(bytes + 40) != Checksum64(bytes, 40)) {
    return Status::Corruption("header at offset 0x0: checksum mismatch");
  }
  if (LoadU32(bytes + 12) != kHeaderBytes) {
    return Status::Corruption("header size " + std::to_string(LoadU32(bytes + 12)) + ", expected " +
                              std::to_string(kHeaderBytes));
  }
  for (size_t offset = 16; offset < 40; offset += 8) {
    if (LoadU64(bytes + offset) != 0) {
      return Status::Corruption("header reserved field at offset " + Hex(offset) + " is not zero");
    }
  }
  return Status::Ok();
}

// Footer, 64 bytes:
//   0 magic[8] | 8 format_major u16 | 10 format_minor u16 | 12 footer_bytes u32 (64)
//   16 generation u64 | 24 metadata_offset u64 | 32 metadata_bytes u64
//   40 metadata_checksum u64 | 48 reserved u64 (0) | 56 footer_checksum u64 = Checksum64([0, 56))
void Footer::EncodeTo(std::string* out) const {
  std::string footer(kFooterMagic.begin(), kFooterMagic.end());
  PutU16(&footer, format_major);
  PutU16(&footer, format_minor);
  PutU32(&footer, static_cast<uint32_t>(kFooterBytes));
  PutU64(&footer, generation);
  PutU64(&footer, metadata_offset);
  PutU64(&footer, metadata_bytes);
  PutU64(&footer, metadata_checksum);
  PutU64(&footer, 0);
  PutU64(&footer, Checksum64(footer.data(), footer.size()));
  out->append(footer);
}

Status Footer::DecodeFrom(const uint8_t* bytes, Footer* footer) {
  constexpr FooterFrame kFrame{kFooterMagic, kFormatMajor, kFooterBytes, "bad footer magic"};
  MOTIF_RETURN_IF_ERROR(
      CheckFooterFrame(bytes, kFrame, &footer->format_major, &footer->format_minor));
  if (LoadU64(bytes + 48) != 0) return Status::Corruption("footer reserved field is not zero");
  footer->generation = LoadU64(bytes + 16);
  footer->metadata_offset = LoadU64(bytes + 24);
  footer->metadata_bytes = LoadU64(bytes + 32);
  footer->metadata_checksum = LoadU64(bytes + 40);
  return Status::Ok();
}

// Block index entry, 40 bytes:
//   0 offset u64 | 8 bytes u64 | 16 first_frame u64 | 24 frame_count u32 | 28 reserved u32 (0)
//   32 checksum u64
void BlockHandle::EncodeTo(std::string* out) const {
  PutU64(out, offset);
  PutU64(out, bytes);
  PutU64(out, first_frame);
  PutU32(out, frame_count);
  PutU32(out, 0);
  PutU64(out, checksum);
}

Status BlockHandle::DecodeFrom(ByteReader* reader, BlockHandle* handle) {
  uint32_t reserved = 0;
  if (!reader->GetU64(&handle->offset) || !reader->GetU64(&handle->bytes) ||
      !reader->GetU64(&handle->first_frame) || !reader->GetU32(&handle->frame_count) ||
      !reader->GetU32(&reserved) || !reader->GetU64(&handle->checksum)) {
    return Status::Corruption("block index entry is truncated");
  }
  if (reserved != 0) return Status::Corruption("block index entry reserved field is not zero");
  return Status::Ok();
}

// Block header, 24 bytes:
//   0 magic "MFBK" | 4 column_count u32 | 8 first_frame u64 | 16 frame_count u32
//   20 reserved u32 (0)
void BlockHeader::EncodeTo(std::string* out) const {
  out->append(kBlockMagic.begin(), kBlockMagic.end());
  PutU32(out, column_count);
  PutU64(out, first_frame);
  PutU32(out, frame_count);
  PutU32(out, 0);
}

Status BlockHeader::DecodeFrom(const uint8_t* bytes, size_t size, BlockHeader* header) {
  if (size < kBlockHeaderBytes) return Status::Corruption("block shorter than its header");
  if (std::memcmp(bytes, kBlockMagic.data(), kBlockMagic.size()) != 0) {
    return Status::Corruption("bad block magic");
  }
  header->column_count = LoadU32(bytes + 4);
  header->first_frame = LoadU64(bytes + 8);
  header->frame_count = LoadU32(bytes + 16);
  if (LoadU32(bytes + 20) != 0) return Status::Corruption("block reserved field is not zero");
  return Status::Ok();
}

}  // namespace motif::frame_file
