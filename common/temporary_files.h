// The temporary files of this process, so that a run ended by SIGTERM, SIGINT or SIGHUP leaves
// none behind: TemporaryPathFor tracks each name it gives, the file system stops tracking a
// name once the file is renamed into place or removed, and the tool's handler (installed by
// RemoveTemporaryFilesOnTermination) unlinks the names still tracked, then ends the process by
// the same signal. The names hold the process id and a counter, so unlinking one that was never
// created, or already renamed, touches nothing else. A kill -9 cannot be handled: such leftovers
// are swept by the next run (RemoveStaleTemporaries, file_util.h).
// Thread-safety: every function may be called from any thread; the handler is lock-free.
#pragma once

#include <string>

namespace motif {

void TrackTemporaryFile(const std::string& path);
void UntrackTemporaryFile(const std::string& path);

// For programs, not libraries (a Python process keeps its own SIGINT): installs the handler of
// SIGTERM, SIGINT and SIGHUP. Idempotent.
void RemoveTemporaryFilesOnTermination();

}  // namespace motif
