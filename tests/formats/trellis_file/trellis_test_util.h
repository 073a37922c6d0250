// Helpers shared by the trellis file tests: seeded synthetic trellises shaped like real ones
// (neighbours in runs of consecutive frames, distances smooth along a run), whole-file writes and
// reads, comparisons within the quantisation bound, and byte-level file helpers.
// Thread-safety: plain functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "common/writable_file.h"
#include "formats/trellis_file/trellis_column.h"
#include "formats/trellis_file/trellis_file_writer.h"

#include "tests/testing/byte_files.h"

namespace motif::testing {

using TrellisColumns = std::vector<std::vector<Neighbour>>;

// Params for a trellis of `frame_count` columns with eps 1 and k_max `k_max`; the other fields
// hold recognisable values so a mix-up shows.
TrellisParams MakeParams(uint64_t frame_count, uint32_t k_max = 1000);

// A trellis of `frame_count` columns whose neighbours come in runs of `min_run` to `max_run`
// consecutive frames at random places, between `min_k` and `max_k` of them a column (capped at
// the frame count), distances in [0, eps] rising from a random minimum towards eps at a run's
// ends, as a pose passes by a similar one. Deterministic in `seed`.
TrellisColumns MakeRunColumns(uint64_t frame_count, float eps, uint32_t min_k, uint32_t max_k,
                              uint64_t seed, uint32_t min_run = 3, uint32_t max_run = 30);

// Columns [first, first + count) of `columns` as one block.
TrellisColumns Slice(const TrellisColumns& columns, uint64_t first, uint64_t count);

// Writes `columns` (params.frame_count of them) as a trellis at `path` in blocks and finishes.
Status WriteTrellis(const std::string& path, const TrellisParams& params,
                    const TrellisColumns& columns, const TrellisFileWriterOptions& options = {});

// Opens `path` and reads every column back.
Result<TrellisColumns> ReadTrellis(const std::string& path);

// Same frames, and every distance within the quantisation bound of the written one (gtest
// assertions; stops at the first difference).
void ExpectSameWithinBound(const TrellisColumns& written, const TrellisColumns& read, float eps);

// NoSyncFileSystem() (common/writable_file.h): fsync skipped, for tests that do not test
// durability; every step still goes through the seam (a FaultInjectingFileSystem over it counts
// the same steps).
using ::motif::NoSyncFileSystem;

// Bytes of this process's mappings of the file at `path` that are resident (the sum of their Rss
// in /proc/self/smaps; pages of the file's page cache not mapped here do not count); -1 if
// /proc/self/smaps cannot be read (not Linux).
int64_t MappedResidentBytes(const std::string& path);

}  // namespace motif::testing
