// ImportIntoArchive: the `import` pipeline. Finds the takes under the given paths, parses them in
// parallel (TBB pipeline, bounded number of takes in flight), maps each onto the archive's
// skeleton, resamples it to the archive's rate, and appends the clips in discovery order, so the
// archive is identical whatever the thread count. Creates the archive (from the first take's
// skeleton and rate, or `fps`) when it does not exist.
//
// Skeleton families: an archive holds one. When the takes it is created from are of several
// (their skeletons read first, ReadSkeletonKind), it is on the CMU body, and every take of
// another family is mapped onto that body (RetargetToCmuBody), at creation and in later
// appends alike. An archive of another family takes only takes of its own skeleton.
//
// All or nothing by default: a take that fails (malformed, another skeleton) stops the import and
// nothing is committed; with skip_bad the failures are reported and the rest committed.
// A take whose content hash is already in the archive is skipped (never imported twice); a new
// take whose file stem is already a clip name gets the name "<stem>~2" ("~3", ...).
// Thread-safety: one call at a time per archive (the writer's lock enforces it across processes).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/status.h"
#include "common/writable_file.h"
#include "formats/import/take_importer.h"

namespace motif {

struct ArchiveImportOptions {
  ImportOptions import;
  double fps = 0;         // archive rate when creating it; 0: the first take's rate
  bool skip_bad = false;  // report failing takes and import the others
  uint32_t block_frames = 4096;
  int threads = 0;  // 0: all cores
  FileSystem* file_system = PosixFileSystem();
  std::function<void(const std::string&)> note;      // messages for the user
  std::function<void(uint64_t, uint64_t)> progress;  // (takes done, takes total)
};

struct ArchiveImportResult {
  bool created = false;
  uint64_t takes_found = 0;
  uint64_t takes_imported = 0;
  uint64_t takes_already_present = 0;
  uint64_t takes_failed = 0;
  uint64_t takes_mapped = 0;  // of those imported, the takes mapped onto the CMU body
  uint64_t frames_added = 0;
  uint64_t archive_clips = 0;
  uint64_t archive_frames = 0;
  double fps = 0;
  std::vector<std::string> failures;  // one message per failed take (skip_bad)
};

Result<ArchiveImportResult> ImportIntoArchive(const std::string& archive_path,
                                              const std::vector<std::string>& inputs,
                                              const ArchiveImportOptions& options);

// The same for takes already listed (DiscoverTakes), in that order. InvalidArgument for an
// empty list.
Result<ArchiveImportResult> ImportTakesIntoArchive(const std::string& archive_path,
                                                   const std::vector<TakeSource>& sources,
                                                   const ArchiveImportOptions& options);

}  // namespace motif
