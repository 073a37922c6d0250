#include "formats/tensor_file/tensor_file_format.h"

#include <cstring>

#include "formats/format_checks/format_checks.h"

namespace motif::tensor_file {

namespace {

bool IsLowerAlnum(char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'); }

// The text of a NUL-padded field: the characters before the first NUL, and whether every byte
// after it is NUL too (a field with no NUL at all is refused: it must end in at least one).
bool ReadPadded(const uint8_t* bytes, size_t size, std::string* text) {
  size_t length = 0;
  while (length < size && bytes[length] != 0) ++length;
  if (length == size) return false;
  for (size_t idx = length; idx < size; ++idx) {
    if (bytes[idx] != 0) return false;
  }
  text->assign(reinterpret_cast<const char*>(bytes), length);
  return true;
}

void PutPadded(std::string* out, const std::string& text, size_t size) {
  out->append(text);
  out->append(size - text.size(), '\0');
}

}  // namespace

std::string KindProblem(const std::string& kind) {
  if (kind.empty() || kind.size() >= kKindBytes) {
    return "kind '" + kind + "' is not 1 to " + std::to_string(kKindBytes - 1) + " characters";
  }
  for (char c : kind) {
    if (!IsLowerAlnum(c) && c != '_' && c != '.' && c != '-') {
      return "kind '" + kind + "' has a character outside [a-z0-9_.-]";
    }
  }
  return "";
}

std::string NameProblem(const std::string& name) {
  if (name.empty() || name.size() >= kNameBytes) {
    return "tensor name '" + name + "' is not 1 to " + std::to_string(kNameBytes - 1) +
           " characters";
  }
  for (char c : name) {
    if (!IsLowerAlnum(c) && c != '_' && c != '.') {
      return "tensor name '" + name + "' has a character outside [a-z0-9_.]";
    }
  }
  return "";
}

// Header, 64 bytes:
//   0 magic[8] | 8 format_major u16 | 10 format_minor u16 | 12 header_bytes u32
//   16 kind[16] (NUL-padded) | 32 tensor_count u32 | 36 flags u32 (0)
//   40 data_bytes u64 | 48 table_checksum u64 | 56 header_checksum u64 of [0, 56)
uint64_t FileHeader::EncodeTo(std::string* out) const {
  std::string header(kFileMagic.begin(), kFileMagic.end());
  PutU16(&header, format_major);
  PutU16(&header, format_minor);
  PutU32(&header, static_cast<uint32_t>(kHeaderBytes));
  PutPadded(&header, kind, kKindBytes);
  PutU32(&header, tensor_count);
  PutU32(&header, 0);
  PutU64(&header, data_bytes);
  PutU64(&header, table_checksum);
  const uint64_t checksum = Checksum64(header.data(), header.size());
  PutU64(&header, checksum);
  out->append(header);
  return checksum;
}

Status FileHeader::DecodeFrom(const uint8_t* bytes, size_t size, FileHeader* header,
                              uint64_t* header_checksum) {
  MOTIF_RETURN_IF_ERROR(
      CheckMagicAndMajor(bytes, size, kFileMagic.data(), "tensor file", kFormatMajor));
  header->format_major = LoadU16(bytes + 8);
  MOTIF_RETURN_IF_ERROR(CheckFileHoldsHeader(size, kHeaderBytes));
  header->format_minor = LoadU16(bytes + 10);
  header->header_bytes = LoadU32(bytes + 12);
  if (header->header_bytes < kHeaderBytes || header->header_bytes > kMaxHeaderBytes ||
      header->header_bytes > size || header->header_bytes % kDataAlignment != 0) {
    return Status::Corruption(
        "header at offset 0x0: header_bytes " + std::to_string(header->header_bytes) +
        " is not a multiple of 8 in [" + std::to_string(kHeaderBytes) + ", min(" +
        std::to_string(kMaxHeaderBytes) + ", file size " + std::to_string(size) + ")]");
  }
  MOTIF_RETURN_IF_ERROR(CheckHeaderChecksum(bytes, header->header_bytes, header_checksum));
  if (!ReadPadded(bytes + 16, kKindBytes, &header->kind) || !KindProblem(header->kind).empty()) {
    return Status::Corruption(
        "header: kind at 0x10 is not 1 to 15 characters of [a-z0-9_.-] "
        "padded with NUL bytes");
  }
  header->tensor_count = LoadU32(bytes + 32);
  const uint32_t flags = LoadU32(bytes + 36);
  if (flags != 0) return Status::Corruption("header: unknown flags " + Hex(flags) + " at 0x24");
  header->data_bytes = LoadU64(bytes + 40);
  header->table_checksum = LoadU64(bytes + 48);
  if (header->tensor_count > kMaxTensors) {
    return Status::Corruption("header: tensor_count " + std::to_string(header->tensor_count) +
                              " exceeds " + std::to_string(kMaxTensors));
  }
  const uint64_t data_start =
      header->header_bytes + static_cast<uint64_t>(header->tensor_count) * kEntryBytes;
  if (!SectionEndsAt(data_start, header->data_bytes, 1, 0, size)) {
    return Status::Corruption(
        "header: " + std::to_string(header->tensor_count) + " table entries and " +
        std::to_string(header->data_bytes) + " data bytes after a header of " +
        std::to_string(header->header_bytes) + " bytes do not make the file's " +
        std::to_string(size) + " bytes (truncated or extended?)");
  }
  return Status::Ok();
}

// Entry, 80 bytes:
//   0 name[32] (NUL-padded) | 32 type u8 | 33 rank u8 | 34 reserved u16 (0) | 36 reserved u32 (0)
//   40 rows u64 | 48 cols u64 | 56 offset u64 | 64 bytes u64 | 72 checksum u64
void TableEntry::EncodeTo(std::string* out) const {
  PutPadded(out, name, kNameBytes);
  PutU8(out, static_cast<uint8_t>(type));
  PutU8(out, rank);
  PutU16(out, 0);
  PutU32(out, 0);
  PutU64(out, rows);
  PutU64(out, cols);
  PutU64(out, offset);
  PutU64(out, bytes);
  PutU64(out, checksum);
}

Status TableEntry::DecodeFrom(const uint8_t* bytes, TableEntry* entry) {
  if (!ReadPadded(bytes, kNameBytes, &entry->name) || !NameProblem(entry->name).empty()) {
    return Status::Corruption(
        "name is not 1 to 31 characters of [a-z0-9_.] padded with NUL "
        "bytes");
  }
  entry->type = static_cast<TensorType>(bytes[32]);
  entry->rank = bytes[33];
  if (TensorTypeBytes(entry->type) == 0) {
    return Status::Corruption("tensor '" + entry->name + "': unknown element type " +
                              std::to_string(bytes[32]));
  }
  if (LoadU16(bytes + 34) != 0 || LoadU32(bytes + 36) != 0) {
    return Status::Corruption("tensor '" + entry->name + "': reserved bytes are not zero");
  }
  entry->rows = LoadU64(bytes + 40);
  entry->cols = LoadU64(bytes + 48);
  entry->offset = LoadU64(bytes + 56);
  entry->bytes = LoadU64(bytes + 64);
  entry->checksum = LoadU64(bytes + 72);
  if (entry->rank != 1 && entry->rank != 2) {
    return Status::Corruption("tensor '" + entry->name + "': rank " + std::to_string(entry->rank) +
                              " is not 1 or 2");
  }
  if (entry->rank == 1 && entry->cols != 1) {
    return Status::Corruption("tensor '" + entry->name + "': a vector with cols " +
                              std::to_string(entry->cols) + " (must be 1)");
  }
  // rows * cols * element bytes == bytes, without overflow.
  const unsigned __int128 expected =
      static_cast<unsigned __int128>(entry->rows) * entry->cols * TensorTypeBytes(entry->type);
  if (expected != entry->bytes) {
    return Status::Corruption("tensor '" + entry->name + "': " + std::to_string(entry->bytes) +
                              " bytes for " + std::to_string(entry->rows) + " x " +
                              std::to_string(entry->cols) + " " + TensorTypeName(entry->type));
  }
  return Status::Ok();
}

}  // namespace motif::tensor_file
