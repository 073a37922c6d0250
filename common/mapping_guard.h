// MappingGuard: keeps a read-only file mapping from killing the process when the file is cut
// (truncated) while it is mapped. Reading a mapped page past the file's new end raises SIGBUS;
// for an address inside a guarded range, the handler puts a zero page there and marks the range
// as cut, so the read goes on with zeros and the reader, which checks `cut()` after each block,
// reports the file as damaged instead (docs/reliability.md, "A file cut under a reader").
// A SIGBUS outside every guarded range goes to the handler that was there before, or kills the
// process as it would have. The handler is installed once, at the first guard.
// Thread-safety: any thread may create, destroy and query guards; the handler is lock-free.
#pragma once

#include <cstdint>

namespace motif {

class MappingGuard {
 public:
  // Guards [begin, begin + bytes). When every one of the fixed number of slots is taken, the
  // range is not guarded (a SIGBUS there kills the process, as without a guard).
  MappingGuard(const void* begin, uint64_t bytes);
  ~MappingGuard();
  MappingGuard(const MappingGuard&) = delete;
  MappingGuard& operator=(const MappingGuard&) = delete;

  // True once a read of the range found the file shorter than the mapping.
  bool cut() const;
  bool guarded() const { return slot_ >= 0; }

 private:
  int slot_ = -1;
};

}  // namespace motif
