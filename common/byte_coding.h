// Little-endian byte coding and checksums shared by every on-disk format (the archive, the
// trellis and the paths file; docs/formats/): fixed-width appends and loads, the XXH3-64
// checksum of every structure, and hexadecimal offsets for error messages. The checks a reader
// makes of a format's structure (magic, footer, sections) are formats/format_checks.
// Thread-safety: pure functions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "common/status.h"

namespace motif {

// XXH3-64 with seed 0.
uint64_t Checksum64(const void* data, size_t size);

// Little-endian appends.
void PutU8(std::string* out, uint8_t value);
void PutU16(std::string* out, uint16_t value);
void PutU32(std::string* out, uint32_t value);
void PutU64(std::string* out, uint64_t value);
void PutF32(std::string* out, float value);
void PutF64(std::string* out, double value);
void PutString(std::string* out, std::string_view value);  // u32 length + bytes

// Little-endian loads; the caller has checked that the bytes are there.
uint16_t LoadU16(const uint8_t* bytes);
uint32_t LoadU32(const uint8_t* bytes);
uint64_t LoadU64(const uint8_t* bytes);

// "0x3f000"
std::string Hex(uint64_t value);

}  // namespace motif
