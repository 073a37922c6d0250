// FaultInjectingFileSystem: forwards to a real FileSystem and fails one chosen step, so tests can
// prove that a failure at any point of a write leaves what was stored before readable and
// unchanged. Every mutating call counts as one step: OpenWritable, WriteAt, Sync, Truncate,
// Rename, SyncParentDir, Remove. A failed WriteAt first writes the first half of its bytes (a
// torn write, as a crash or a full disk would leave). With `sticky`, every step after the failing
// one fails too (a disk that stays full); otherwise later steps succeed (cleanup can run).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "common/writable_file.h"

namespace motif::testing {

class FaultInjectingFileSystem final : public FileSystem {
 public:
  explicit FaultInjectingFileSystem(FileSystem* base = PosixFileSystem()) : base_(base) {}

  // Fails step number `step` (0-based); -1 never fails.
  void FailAt(int64_t step, bool sticky = false) {
    fail_at_ = step;
    sticky_ = sticky;
  }
  int64_t steps() const { return steps_; }
  bool injected() const { return injected_; }

  Result<std::unique_ptr<WritableFile>> OpenWritable(const std::string& path,
                                                     OpenMode mode) override;
  Status Rename(const std::string& from, const std::string& to) override;
  Status SyncParentDir(const std::string& path) override;
  Status Remove(const std::string& path) override;

  // Counts one step; returns the injected error if this step is to fail.
  Status Step(const std::string& what);

 private:
  FileSystem* base_;
  int64_t fail_at_ = -1;
  bool sticky_ = false;
  int64_t steps_ = 0;
  bool injected_ = false;
};

}  // namespace motif::testing
