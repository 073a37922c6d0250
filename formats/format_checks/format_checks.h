// The structural checks every binary format's reader makes before it trusts a byte, shared by the
// archive (.mfs), the trellis (.mtr), the paths file (.mpa) and the tensor file (docs/formats/):
// the file's identity (magic and major version at offset 0), a header that ends in its own
// checksum, the 64-byte footer frame of the footer-indexed formats (magic, version, size and a
// checksum of the rest), and a section that must end exactly where the next structure starts.
// Each returns the same Status codes and messages the formats' specs list under "Reader duties";
// messages name the structure but not the file (callers add it). Nothing here touches files.
// Thread-safety: pure functions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/status.h"

namespace motif {

// The first checks of a file format's reader, in this order: the file is not empty, starts with
// the 8-byte `magic` (Corruption "bad magic at offset 0x0: not a <what>"), holds the u16 major
// version at offset 8, and that version is `major` (NotSupported "unsupported format major
// version N (this reader knows M)": exit code 15, a newer tool's file). `size` bytes are available
// at `bytes`.
Status CheckMagicAndMajor(const uint8_t* bytes, size_t size, const uint8_t* magic,
                          const std::string& what, uint16_t major);

// A file of `size` bytes holds a header of `header_bytes`. Corruption: "file of N bytes is
// shorter than the header (M bytes): truncated".
Status CheckFileHoldsHeader(size_t size, size_t header_bytes);

// The last 8 bytes of the `header_bytes` at `bytes` are the Checksum64 of the bytes before them;
// sets *stored to them (may be null). Corruption: "header at offset 0x0: checksum mismatch
// (stored at <offset>)". Precondition: header_bytes >= 8, all of it available.
Status CheckHeaderChecksum(const uint8_t* bytes, size_t header_bytes, uint64_t* stored = nullptr);

// The frame of a footer-indexed format's footer:
//   0 magic[8] | 8 format_major u16 | 10 format_minor u16 | 12 footer_bytes u32
//   ... the format's fields ... | footer_bytes - 8: footer checksum u64 of the bytes before it
struct FooterFrame {
  std::array<uint8_t, 8> magic;
  uint16_t major = 0;         // the only major version the reader knows
  uint32_t footer_bytes = 0;  // the frame's size, checksum included
  // The Corruption message of a footer without the magic (e.g. a hint at what it may be).
  const char* bad_magic = "bad footer magic";
};

// Checks, in this order, the magic, the checksum, the major version and the size field of the
// footer frame at `bytes` (frame.footer_bytes available), and sets *format_major and
// *format_minor as soon as they are read (before the version check). Corruption:
// frame.bad_magic, "footer checksum mismatch", "footer has unsupported format major version N",
// "footer size N, expected M".
Status CheckFooterFrame(const uint8_t* bytes, const FooterFrame& frame, uint16_t* format_major,
                        uint16_t* format_minor);

// True if a section of `entry_count` entries of `entry_bytes` (1: a section of entry_count bytes)
// starting at `offset` lies at or after `lowest` and ends exactly at `end` (no product is formed,
// so a crafted count cannot wrap into a match). Callers say what does not fit, and where.
bool SectionEndsAt(uint64_t offset, uint64_t entry_count, uint64_t entry_bytes, uint64_t lowest,
                   uint64_t end);

}  // namespace motif
