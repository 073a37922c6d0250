// SearchCache: what `motifmine reindex` keeps between runs so that an update costs its new frames
// and not the whole archive (docs/formats/search_cache.md): the pose features of every frame
// (96 bytes a frame for CMU takes), the LSH tables (10 bytes a frame and table, 14 with position
// codes), and each trellis column's threshold (the distance a new frame must beat to enter it).
// Without it every update decodes the whole archive again, hashes every frame into the tables
// and decodes the whole trellis: at 10^6 frames more than the rest of the update.
//
// One file per version (OUTDIR/v<N>/search.msc), written after the trellis, read by the next
// run. It is a cache: written without fsync (a torn or lost file fails its checksum and is
// rebuilt), named by nothing a reader uses, and checked against what it must describe (the
// archive version, the joint weights, the hash family, the trellis) before it is used.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "common/writable_file.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/lsh_index.h"

namespace motif {

// The cache's name in a reindex version's folder.
inline constexpr char kSearchCacheFileName[] = "search.msc";

// What a cache describes; a cache is used only when every field equals what the run needs.
struct SearchCacheKey {
  uint64_t archive_identity = 0;  // FrameFileSummary::identity of the archive version
  uint64_t weights_hash = 0;      // WeightsHash of the pose-distance weights
  std::string family;             // DescribeLshOptions of the resolved LSH options; "" without
  bool operator==(const SearchCacheKey&) const = default;
};

struct SearchCache {
  SearchCacheKey key;
  PoseFeatures features;
  std::vector<LshTableEntries> tables;  // empty without an index
  bool position_codes = false;          // the tables hold position codes
  uint64_t trellis_identity = 0;        // the trellis the thresholds belong to; 0: none
  std::vector<float> thresholds;        // one per column (frame) when trellis_identity != 0
};

// Writes the cache to `path` (a temporary file renamed into place, not synced). `index` may be
// null (exact search), `thresholds` empty (unknown). IOError / ResourceExhausted; the temporary
// file is removed on failure.
Status WriteSearchCache(const std::string& path, const SearchCacheKey& key,
                        const PoseFeatures& features, const LshIndex* index,
                        uint64_t trellis_identity, const std::vector<float>& thresholds,
                        FileSystem* file_system = PosixFileSystem());

// Reads and checks a cache (magic, version, sizes, checksum of every byte). NotFound; Corruption
// naming the file for anything that does not check.
Result<SearchCache> ReadSearchCache(const std::string& path);

}  // namespace motif
