// WritableFile and FileSystem: the seam through which motifmine writes to disk. Every write, sync,
// truncate, rename and directory sync of the archive writer and of atomic file replacement goes
// through a FileSystem, so a test can fail any single step (tests/testing/fault_injection.h) and
// check that what was already stored is untouched. PosixFileSystem() is the real one.
// Thread-safety: a WritableFile is used by one thread at a time; PosixFileSystem is stateless.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "common/status.h"

namespace motif {

class WritableFile {
 public:
  virtual ~WritableFile() = default;
  // Writes all `size` bytes at `offset`. IOError / ResourceExhausted (disk full) on failure; the
  // bytes may then be partly written.
  virtual Status WriteAt(uint64_t offset, const void* data, size_t size) = 0;
  // fsync(2): the data is durable when this returns OK.
  virtual Status Sync() = 0;
  // Sets the file's length to `size` bytes.
  virtual Status Truncate(uint64_t size) = 0;
  // Current length in bytes.
  virtual Result<uint64_t> Size() = 0;
  // Releases the descriptor. Called by the destructor if not called before.
  virtual Status Close() = 0;
  virtual const std::string& path() const = 0;
};

enum class OpenMode {
  kCreateExclusive,  // O_CREAT | O_EXCL: fails with IOError if the file exists
  kExisting,         // the file must exist; opened read-write, not truncated
};

class FileSystem {
 public:
  virtual ~FileSystem() = default;
  virtual Result<std::unique_ptr<WritableFile>> OpenWritable(const std::string& path,
                                                             OpenMode mode) = 0;
  // rename(2): atomically replaces `to`.
  virtual Status Rename(const std::string& from, const std::string& to) = 0;
  // The same, unless `to` exists: then Busy, and nothing changes. The real file system does it
  // in one step (renameat2 RENAME_NOREPLACE); this default, for file systems that wrap another
  // in tests, checks first.
  virtual Status RenameNoReplace(const std::string& from, const std::string& to);
  // fsync(2) on the directory that holds `path`, so a rename into it is durable.
  virtual Status SyncParentDir(const std::string& path) = 0;
  // unlink(2); a missing file is not an error.
  virtual Status Remove(const std::string& path) = 0;
};

// The real file system (POSIX calls). Never null; lives for the whole program.
FileSystem* PosixFileSystem();

// The real file system with fsync (of files and directories) made a no-op: for throwaway files
// in tests that do not test durability and in benchmarks, so that they stay fast on a busy disk
// (and do not load a shared one). Every other step is PosixFileSystem()'s. Lives for the whole
// program.
FileSystem* NoSyncFileSystem();

}  // namespace motif
