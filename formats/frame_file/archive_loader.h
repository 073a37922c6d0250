// LoadArchive: finds the committed version of a motion archive in its bytes and validates it
// (docs/formats/frame_file.md, "Reader duties"): the header's fixed part, then the commit slots
// newest generation first; for each, its committed length, footer, metadata checksum and
// metadata. The first slot that validates is the archive; if it is not the newest written slot
// whose own checksum is valid, `fallback_reason` says why the newer one was passed over.
// Bytes after the chosen committed length (an interrupted append) are ignored.
// Used by FrameFileReader (over its mapping) and by FrameFileWriter::OpenForAppend.
// Thread-safety: a pure function over bytes the caller keeps alive.
#pragma once

#include <cstdint>
#include <string>

#include "common/status.h"
#include "formats/frame_file/archive_metadata.h"
#include "formats/frame_file/frame_file_format.h"

namespace motif::frame_file {

struct LoadedArchive {
  FileHeader header;    // fixed part and both slots as found (a damaged slot reads empty)
  int active_slot = 0;  // index of the slot in use (-1: a version named by LoadArchiveCommit)
  CommitSlot slot;      // header.slots[active_slot]
  Footer footer;
  ArchiveMetadata metadata;
  uint64_t file_bytes = 0;      // the whole file, including any uncommitted tail
  uint64_t max_generation = 0;  // the highest generation of any slot with a valid checksum
  std::string fallback_reason;  // non-empty if a newer valid slot failed validation
  // Non-empty if the version opened ends the file but its commit slot is damaged (it was read
  // from its footer): the data is whole, the damage is reported by Verify, and the next commit
  // goes to the other slot.
  std::string damaged_slot_reason;
};

// `data` holds the file's `size` bytes; `path` is used in messages only. Corruption naming the
// file and the offset of the first failed check (of the newest slot if none validates).
Result<LoadedArchive> LoadArchive(const std::string& path, const uint8_t* data, uint64_t size);

// The earlier version of the archive committed as `generation` with `committed_length` bytes:
// appends never rewrite what lies before their committed end, so every version's footer and
// metadata stay in the file (frame_file.md section 7). Validated as a commit slot's version
// is (checks 9 to 12), the header's fixed part first. Corruption naming the file if that
// version is not there (another file, or a truncated one).
Result<LoadedArchive> LoadArchiveCommit(const std::string& path, const uint8_t* data, uint64_t size,
                                        uint64_t generation, uint64_t committed_length);

}  // namespace motif::frame_file
