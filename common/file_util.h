// Whole-file helpers: read a file into memory, and replace a file atomically (write a temporary
// file beside it, fsync, rename over the target, fsync the directory), so a reader sees either the
// old content or the new one, never a half-written file.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/status.h"
#include "common/writable_file.h"

namespace motif {

// Reads the whole file. NotFound if it does not exist; InvalidArgument "<path>: is a directory,
// not a file" or "<path>: not a regular file (a FIFO, device or socket)" without blocking or
// reading it, or "<path>: N bytes, more than the M allowed" for a file larger than `max_bytes`
// (checked on its size before reading, and again while reading a file that grows); IOError
// otherwise.
Result<std::string> ReadFileToString(const std::string& path, uint64_t max_bytes = UINT64_MAX);
// The same, for a file that must be a regular file: NotFound "<path>: no such file", IOError
// "<path>: not a regular file" (a folder, a device), or ReadFileToString's errors.
Result<std::string> ReadRegularFile(const std::string& path);

// A temporary path beside `path`, unique to this process and call: "<path>.tmp-<pid>-<n>".
std::string TemporaryPathFor(const std::string& path);

// Atomically replaces `path` with `content`. On any failure the old file (if any) is untouched and
// the temporary file is removed. IOError / ResourceExhausted on failure.
Status AtomicWriteFile(const std::string& path, std::string_view content,
                       FileSystem* file_system = PosixFileSystem());

// Removes what killed runs left in `dir`: the temporary files ("<name>.tmp-<pid>-<n>", see
// TemporaryPathFor, and a writer's own "<name>.tmp-<pid>-<n>.tmp-<pid>-<m>") of the given file
// names, when the process that made them is gone. A killed run can leave a whole half-written
// archive behind, and no later run would ever reuse or remove it. Files of a process that still
// runs are left alone. Best effort: a file that cannot be removed is skipped.
void RemoveStaleTemporaries(const std::string& dir, const std::vector<std::string>& names);

}  // namespace motif
