#include "engine/trellis/distributed_columns.h"

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "common/seconds_since.h"
#include "engine/trellis/block_write_queue.h"
#include "formats/trellis_file/trellis_block_codec.h"

namespace motif {
namespace {

using Columns = std::vector<std::vector<Neighbour>>;

uint64_t BlockFirstColumn(uint64_t block, const DistributedColumnsPlan& plan) {
  return block * plan.block_columns;
}

uint64_t BlockColumnCount(uint64_t block, const DistributedColumnsPlan& plan) {
  return std::min<uint64_t>(plan.block_columns, plan.frame_count - BlockFirstColumn(block, plan));
}

int OwnerOf(uint64_t block, const RankGroup& ranks) {
  return static_cast<int>(block % static_cast<uint64_t>(ranks.size()));
}

Result<Columns> SearchBlock(const NeighbourSearch& search, uint64_t block,
                            const DistributedColumnsPlan& plan, DistributedColumnsReport* report) {
  const auto start = std::chrono::steady_clock::now();
  SearchStats* stats = &report->stats;
  ++report->blocks_searched;
  Columns columns(BlockColumnCount(block, plan));
  MOTIF_RETURN_IF_ERROR(
      search.SearchColumns(BlockFirstColumn(block, plan), columns.size(), &columns, stats));
  for (std::vector<Neighbour>& column : columns) column.shrink_to_fit();
  report->search_seconds += SecondsSince(start);
  return columns;
}

// Rank 0: every block in column order, its own searched here, the others' received.
Status WriteEveryBlock(const NeighbourSearch& search, RankGroup* ranks,
                       const DistributedColumnsPlan& plan, TrellisFileWriter* writer,
                       const std::function<void(uint64_t, uint64_t)>& progress,
                       DistributedColumnsReport* report) {
  BlockWriteQueue queue(writer);
  const uint64_t block_count = (plan.frame_count + plan.block_columns - 1) / plan.block_columns;
  for (uint64_t block = plan.first_column / plan.block_columns; block < block_count; ++block) {
    const int owner = OwnerOf(block, *ranks);
    Columns columns;
    std::string bytes;
    if (owner == 0) {
      MOTIF_ASSIGN_OR_RETURN(columns, SearchBlock(search, block, plan, report));
    } else {
      const auto start = std::chrono::steady_clock::now();
      MOTIF_ASSIGN_OR_RETURN(bytes, ranks->ReceiveFrom(owner, block));
      report->receive_wait_seconds += SecondsSince(start);
    }
    MOTIF_RETURN_IF_ERROR(queue.Wait(&report->write_wait_seconds));
    if (block > plan.first_column / plan.block_columns && progress) {
      progress(BlockFirstColumn(block, plan), plan.frame_count);
    }
    if (owner == 0) {
      queue.StartColumns(std::move(columns));
    } else {
      queue.StartEncoded(std::move(bytes));
    }
  }
  MOTIF_RETURN_IF_ERROR(queue.Wait(&report->write_wait_seconds));
  report->write_seconds = queue.write_seconds();
  if (progress) progress(plan.frame_count, plan.frame_count);
  return Status::Ok();
}

// Another rank: its blocks, encoded as the file stores them, sent to rank 0.
Status SendOwnBlocks(const NeighbourSearch& search, RankGroup* ranks,
                     const DistributedColumnsPlan& plan, DistributedColumnsReport* report) {
  trellis_file::BlockEncoder encoder(plan.zstd_level);
  const uint64_t block_count = (plan.frame_count + plan.block_columns - 1) / plan.block_columns;
  for (uint64_t block = plan.first_column / plan.block_columns; block < block_count; ++block) {
    if (OwnerOf(block, *ranks) != ranks->rank()) continue;
    MOTIF_ASSIGN_OR_RETURN(Columns columns, SearchBlock(search, block, plan, report));
    std::string bytes;
    trellis_file::BlockHandle handle;
    MOTIF_RETURN_IF_ERROR(
        encoder.Encode(BlockFirstColumn(block, plan), columns, plan.eps, &bytes, &handle));
    MOTIF_RETURN_IF_ERROR(ranks->SendToRoot(block, std::move(bytes)));
  }
  return ranks->FinishSends();
}

}  // namespace

Result<DistributedColumnsReport> SearchColumnsAcrossRanks(
    const NeighbourSearch& search, RankGroup* ranks, const DistributedColumnsPlan& plan,
    TrellisFileWriter* writer, const std::function<void(uint64_t, uint64_t)>& progress) {
  if (plan.block_columns == 0 || plan.first_column % plan.block_columns != 0) {
    return Status::InvalidArgument("distributed trellis: the build must start at a block");
  }
  DistributedColumnsReport report;
  if (ranks->rank() == 0) {
    if (writer == nullptr) return Status::InvalidArgument("distributed trellis: rank 0 writes");
    MOTIF_RETURN_IF_ERROR(WriteEveryBlock(search, ranks, plan, writer, progress, &report));
  } else {
    MOTIF_RETURN_IF_ERROR(SendOwnBlocks(search, ranks, plan, &report));
  }
  // The work counters of every rank, so that rank 0 reports what one process would.
  std::vector<uint64_t> counters = {report.stats.columns, report.stats.distance_evaluations,
                                    report.stats.neighbours, report.stats.capped_columns};
  MOTIF_RETURN_IF_ERROR(ranks->SumToRoot(&counters));
  report.stats = {counters[0], counters[1], counters[2], counters[3]};
  return report;
}

}  // namespace motif
