// MappedFile: a whole file memory-mapped read-only (Boost.Interprocess), as the archive, trellis
// readers use it: opened with errors that name the file, and with a way to give the pages of
// bytes already read back to the kernel, so that streaming through a file larger than memory
// does not keep it resident.
// Thread-safety: const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

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

  // Gives the whole pages of bytes [begin_offset, end_offset) back to the kernel (best effort;
  // they are read from the file again if touched) and returns the page-aligned end released.
  uint64_t ReleasePages(uint64_t begin_offset, uint64_t end_offset) const;

 private:
  struct Mapping;
  MappedFile() = default;
  std::unique_ptr<Mapping> mapping_;
  const uint8_t* data_ = nullptr;
  uint64_t size_ = 0;
};

}  // namespace motif
