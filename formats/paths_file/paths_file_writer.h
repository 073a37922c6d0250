// WritePathsFile: the path grower's candidates (formats/paths_file/path_candidate.h) as a paths
// file
// (.mpa, docs/formats/paths_file.md): a header naming the trellis the paths were grown from
// and the grow parameters, then the candidates as one zstd-compressed section of delta-coded
// records, everything checksummed. The file is small (tens of bytes a thousand candidates) and
// is written whole and atomically: temporary file, fsync, rename, directory fsync; a reader
// sees the old file or the new one, never a half-written one.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "common/writable_file.h"
#include "formats/paths_file/path_candidate.h"
#include "formats/paths_file/paths_params.h"

namespace motif {

struct PathsFileWriterOptions {
  int zstd_level = 3;
  FileSystem* file_system = PosixFileSystem();
};

// Writes `candidates` to `path`, replacing any file there atomically. InvalidArgument (nothing
// is written) if the params are out of range or a candidate breaks the file's rules: sorted
// strictly by (top_start, match_start, top_end, match_end, root_column, root_frame), both ends
// within frame_count, both lengths at least min_length, root_column <= top_start, root_frame
// below frame_count. IOError / ResourceExhausted from the file system.
Status WritePathsFile(const std::string& path, const PathsParams& params,
                      const std::vector<PathCandidate>& candidates,
                      const PathsFileWriterOptions& options = {});

// The bytes WritePathsFile writes (for tests and for the spec's worked example).
Result<std::string> EncodePathsFile(const PathsParams& params,
                                    const std::vector<PathCandidate>& candidates,
                                    int zstd_level = 3);

}  // namespace motif
