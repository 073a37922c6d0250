// Little-endian byte coding and checksums shared by every on-disk format (the archive, the
// trellis and the paths file; docs/formats/): fixed-width appends and loads, the XXH3-64
// checksum of every structure, and hexadecimal offsets for error messages.
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

// The first checks of a file format's reader, in this order: the file is not empty, starts with
// the 8-byte `magic` (Corruption "bad magic at offset 0x0: not a <what>"), holds the u16 major
// version at offset 8, and that version is `major` (NotSupported "unsupported format major
// version N (this reader knows M)": exit code 15, a newer tool's file). `size` bytes are available
// at `bytes`.
Status CheckMagicAndMajor(const uint8_t* bytes, size_t size, const uint8_t* magic,
                          const std::string& what, uint16_t major);

}  // namespace motif
