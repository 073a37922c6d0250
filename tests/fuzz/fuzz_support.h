// Helpers shared by the fuzz targets (tests/fuzz/*_fuzz.cc, docs/reliability.md "Fuzzing"):
// property checks that turn a broken promise into a crash the fuzzer reports, a per-process
// scratch file for readers that open a path, and in-place little-endian stores for the targets
// that repair checksums before handing bytes to a reader.
// Thread-safety: a fuzz target runs one input at a time; ScratchFile is not thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "common/status.h"

namespace motif::fuzz {

// Prints "fuzz check failed: <what>: <detail>" and aborts: libFuzzer records the input.
[[noreturn]] void Fail(std::string_view what, std::string_view detail);

// The error contract of a parser or reader: OK, or `expected_code` with a message that names
// `file_name`. Anything else fails (Fail) with `where` in the report.
void CheckError(const Status& status, Status::Code expected_code, std::string_view file_name,
                std::string_view where);

// A file under $TMPDIR (or /tmp) named motif-fuzz-<pid>-<tag><extension>, rewritten for each
// input and removed when the object is destroyed (a crashed run leaves it behind).
class ScratchFile {
 public:
  ScratchFile(std::string_view tag, std::string_view extension);
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  // Replaces the file's contents with `size` bytes; fails (Fail) if it cannot.
  void Write(const uint8_t* data, size_t size);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Little-endian stores into a buffer the caller has sized.
void StoreU64(uint8_t* bytes, uint64_t value);

// Whether bytes [offset, offset + length) lie within the first `size` bytes (overflow-safe).
inline bool InRange(uint64_t offset, uint64_t length, uint64_t size) {
  return offset <= size && length <= size - offset;
}

}  // namespace motif::fuzz
