#include "common/byte_coding.h"

#include <bit>
#include <cstdio>
#include <cstring>

#include <xxhash.h>

namespace motif {

uint64_t Checksum64(const void* data, size_t size) { return XXH3_64bits(data, size); }

void PutU8(std::string* out, uint8_t value) { out->push_back(static_cast<char>(value)); }

void PutU16(std::string* out, uint16_t value) {
  for (int byte_idx = 0; byte_idx < 2; ++byte_idx) {
    out->push_back(static_cast<char>((value >> (8 * byte_idx)) & 0xFF));
  }
}

void PutU32(std::string* out, uint32_t value) {
  for (int byte_idx = 0; byte_idx < 4; ++byte_idx) {
    out->push_back(static_cast<char>((value >> (8 * byte_idx)) & 0xFF));
  }
}

void PutU64(std::string* out, uint64_t value) {
  for (int byte_idx = 0; byte_idx < 8; ++byte_idx) {
    out->push_back(static_cast<char>((value >> (8 * byte_idx)) & 0xFF));
  }
}

void PutF32(std::string* out, float value) { PutU32(out, std::bit_cast<uint32_t>(value)); }
void PutF64(std::string* out, double value) { PutU64(out, std::bit_cast<uint64_t>(value)); }

void PutString(std::string* out, std::string_view value) {
  PutU32(out, static_cast<uint32_t>(value.size()));
  out->append(value.data(), value.size());
}

uint16_t LoadU16(const uint8_t* bytes) { return static_cast<uint16_t>(bytes[0] | bytes[1] << 8); }

uint32_t LoadU32(const uint8_t* bytes) {
  return static_cast<uint32_t>(bytes[0]) | static_cast<uint32_t>(bytes[1]) << 8 |
         static_cast<uint32_t>(bytes[2]) << 16 | static_cast<uint32_t>(bytes[3]) << 24;
}

uint64_t LoadU64(const uint8_t* bytes) {
  return static_cast<uint64_t>(LoadU32(bytes)) | static_cast<uint64_t>(LoadU32(bytes + 4)) << 32;
}

std::string Hex(uint64_t value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "0x%llx", static_cast<unsigned long long>(value));
  return buffer;
}

}  // namespace motif
