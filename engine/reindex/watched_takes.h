// ScanWatchedFolder: which takes of a watched folder `motifmine reindex` should import. Every
// BVH / AMC file under the folder (DiscoverTakes) is hashed as the importer hashes it (XXH3-64 of
// the file's bytes, formats/import/take_importer.h) and compared with the archive's clips:
//   * known: its content is in the archive already (under any name): skipped, so a re-run
//     never imports a take twice;
//   * changed: a clip was imported from this very file (same absolute path) with other
//     content: reported, not imported (the archive keeps what was mined; a user who means the
//     new content gives the file another name);
//   * settling: modified less than min_age_seconds ago, perhaps still being copied in: left
//     for the next run;
//   * new: imported, in path order.
// Thread-safety: a pure function of the files.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "formats/import/take_importer.h"
#include "formats/motion/pose_frames.h"

namespace motif {

struct WatchScan {
  std::vector<TakeSource> new_takes;  // absolute paths, in path order
  uint64_t known_takes = 0;
  std::vector<std::string> changed;   // one message per changed file
  std::vector<std::string> settling;  // files left for the next run
  uint64_t scanned_bytes = 0;         // read to hash
};

// The absolute, normalised form of `path` under which the importer stores a watched take.
std::string WatchedPath(const std::string& path);

// NotFound if `dir` does not exist; InvalidArgument from DiscoverTakes (e.g. an AMC file with no
// ASF to pair); IOError if a file cannot be read.
Result<WatchScan> ScanWatchedFolder(const std::string& dir, const std::vector<ClipInfo>& clips,
                                    const ImportOptions& options, double min_age_seconds);

}  // namespace motif
