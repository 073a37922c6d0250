// ExclusiveFileLock: an exclusive, non-blocking flock(2) on a file, held through a descriptor of
// its own, so one writer at a time works on an archive or a trellis. flock, not fcntl: an fcntl
// lock is dropped when *any* descriptor of the file in this process is closed (a reader's
// mapping, the writer's WritableFile); a flock only with this descriptor.
// Thread-safety: one owner; released by Release() or the destructor.
#pragma once

#include <string>

#include "common/status.h"

namespace motif {

class ExclusiveFileLock {
 public:
  ExclusiveFileLock() = default;
  ~ExclusiveFileLock() { Release(); }
  ExclusiveFileLock(const ExclusiveFileLock&) = delete;
  ExclusiveFileLock& operator=(const ExclusiveFileLock&) = delete;

  // Locks `path` (which must exist unless `create`: NotFound otherwise; with `create` a missing
  // file is created empty). If another process or descriptor holds the lock: Busy
  // "<path>: <held_message>", at once (the lock is never waited for).
  Status Acquire(const std::string& path, const std::string& held_message, bool create = false);
  void Release();

 private:
  int fd_ = -1;
};

}  // namespace motif
