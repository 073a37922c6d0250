#include "formats/format_checks/format_checks.h"

#include <cstring>

#include "common/byte_coding.h"

namespace motif {

Status CheckMagicAndMajor(const uint8_t* bytes, size_t size, const uint8_t* magic,
                          const std::string& what, uint16_t major) {
  if (size == 0) return Status::Corruption("empty file");
  if (size < 8 || std::memcmp(bytes, magic, 8) != 0) {
    return Status::Corruption("bad magic at offset 0x0: not a " + what);
  }
  if (size < 10) {
    return Status::Corruption("file of " + std::to_string(size) + " bytes: truncated header");
  }
  const uint16_t found = LoadU16(bytes + 8);
  if (found != major) {
    return Status::NotSupported("unsupported format major version " + std::to_string(found) +
                                " (this reader knows " + std::to_string(major) + ")");
  }
  return Status::Ok();
}

Status CheckFileHoldsHeader(size_t size, size_t header_bytes) {
  if (size >= header_bytes) return Status::Ok();
  return Status::Corruption("file of " + std::to_string(size) +
                            " bytes is shorter than the header (" + std::to_string(header_bytes) +
                            " bytes): truncated");
}

Status CheckHeaderChecksum(const uint8_t* bytes, size_t header_bytes, uint64_t* stored) {
  const size_t checksum_offset = header_bytes - 8;
  const uint64_t checksum = LoadU64(bytes + checksum_offset);
  if (stored != nullptr) *stored = checksum;
  if (Checksum64(bytes, checksum_offset) != checksum) {
    return Status::Corruption("header at offset 0x0: checksum mismatch (stored at " +
                              Hex(checksum_offset) + ")");
  }
  return Status::Ok();
}

Status CheckFooterFrame(const uint8_t* bytes, const FooterFrame& frame, uint16_t* format_major,
                        uint16_t* format_minor) {
  if (std::memcmp(bytes, frame.magic.data(), frame.magic.size()) != 0) {
    return Status::Corruption(frame.bad_magic);
  }
  const size_t checksum_offset = frame.footer_bytes - 8;
  if (LoadU64(bytes + checksum_offset) != Checksum64(bytes, checksum_offset)) {
    return Status::Corruption("footer checksum mismatch");
  }
  *format_major = LoadU16(bytes + 8);
  *format_minor = LoadU16(bytes + 10);
  if (*format_major != frame.major) {
    return Status::Corruption("footer has unsupported format major version " +
                              std::to_string(*format_major));
  }
  if (LoadU32(bytes + 12) != frame.footer_bytes) {
    return Status::Corruption("footer size " + std::to_string(LoadU32(bytes + 12)) + ", expected " +
                              std::to_string(frame.footer_bytes));
  }
  return Status::Ok();
}

bool SectionEndsAt(uint64_t offset, uint64_t entry_count, uint64_t entry_bytes, uint64_t lowest,
                   uint64_t end) {
  if (offset < lowest || offset > end) return false;
  const uint64_t bytes = end - offset;
  return bytes % entry_bytes == 0 && bytes / entry_bytes == entry_count;
}

}  // namespace motif
