// MappedFile: a whole file memory-mapped read-only (Boost.Interprocess), as the archive, trellis
// readers use it: opened with errors that name the file, and with a way to give the pages of
// bytes already read back to the kernel, so that streaming through a file larger than memory
// does not keep it resident. A file cut (truncated) while mapped does not kill the process with
// SIGBUS: the pages past its new end read as zeros and `CheckNotCut` reports it (mapping_guard.h).
// Thread-safety: const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "common/mapping_guard.h"
#include "common/status.h"

namespace motif {

class MappedFile {
 public:
  // NotFound: no file; IOError: not a regular file, no size, cannot map. An empty file maps to
  // data() == nullptr, size() == 0.
  static Result<std::unique_ptr<MappedFile>> Open(const std::string& path);
  ~MappedFile();

  const uint8_t* data() const { return data_; }
  uint64_t size() const { return size_; }
  const std::string& path() const { return path_; }

  // True once a read found the file shorter than the mapping (what it read there is zeros).
  bool cut() const { return guard_ != nullptr && guard_->cut(); }
  // Corruption naming the file when it is cut: a read found it shorter (`cut()`), or it is now
  // shorter than when mapped. A reader calls this after each block it decodes when `cut()`, and
  // before it reports any damage in what it read, so that a cut is named as such.
  Status CheckNotCut() const;
  // `read` (the status of decoding bytes of this file), unless the file was cut: then the cut,
  // which explains the zeros read. The one check every reader makes after reading.
  Status ExplainRead(Status read) const;

  // Gives the whole pages of bytes [begin_offset, end_offset) back to the kernel (best effort;
  // they are read from the file again if touched) and returns the page-aligned end released.
  uint64_t ReleasePages(uint64_t begin_offset, uint64_t end_offset) const;

 private:
  struct Mapping;
  MappedFile() = default;
  std::unique_ptr<Mapping> mapping_;
  std::unique_ptr<MappingGuard> guard_;  // after mapping_: unguards before the unmapping
  std::string path_;
  const uint8_t* data_ = nullptr;
  uint64_t size_ = 0;
};

}  // namespace motif
