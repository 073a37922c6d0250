// The trellis columns of a distributed run (motifmine-mpi; docs/design/distributed.md): the
// column blocks are dealt round robin, block b (columns [b * block_columns, ...)) to rank
// b mod R, so every rank gets the same share of the archive's easy and hard stretches. A rank
// searches its blocks with its own copy of the search and encodes each one as the trellis file
// stores it; the other ranks send theirs to rank 0, which appends every block in column order to
// the one trellis file (its own blocks on a writer thread, as a single process does). The file
// is byte for byte the single process's (each column depends only on the data, the parameters
// and the seed), and an interrupted run resumes after its last block like any other.
#pragma once

#include <cstdint>
#include <functional>

#include "common/rank_group.h"
#include "common/status.h"
#include "engine/distance/neighbour_search.h"
#include "formats/trellis_file/trellis_file_writer.h"

namespace motif {

struct DistributedColumnsPlan {
  uint64_t first_column = 0;  // where the build starts (a block boundary: 0, or a resume)
  uint64_t frame_count = 0;
  uint32_t block_columns = 0;
  float eps = 0;       // the trellis's, which the blocks are encoded with
  int zstd_level = 3;  // the writer's (TrellisFileWriterOptions)
};

struct DistributedColumnsReport {
  SearchStats stats;                // summed over the ranks (rank 0's report)
  double receive_wait_seconds = 0;  // rank 0: waiting for other ranks' blocks
  double write_wait_seconds = 0;
  double write_seconds =
      0;  // rank 0: its writer thread's time writing    // rank 0: waiting for its writer thread
  uint64_t blocks_searched = 0;  // by this rank
  double search_seconds = 0;     // this rank's time in the search of its blocks
};

// Collective. Rank 0 passes the writer (it writes every block, then the caller calls Finish);
// the other ranks pass null. `progress(done, total)` on rank 0, in columns, after each write.
Result<DistributedColumnsReport> SearchColumnsAcrossRanks(
    const NeighbourSearch& search, RankGroup* ranks, const DistributedColumnsPlan& plan,
    TrellisFileWriter* writer, const std::function<void(uint64_t, uint64_t)>& progress);

}  // namespace motif
