// RankGroup: the processes ("ranks") of one distributed mining run, as the stages that share
// their work see them (docs/design/distributed.md). The stages depend only on this interface;
// motifmine-mpi implements it over MPI (engine/distributed/mpi_rank_group.h). Rank 0 is the
// root: it owns the output folder and writes every file.
//
// Every method but rank(), size() and bytes_sent() is collective or point to point as stated;
// ranks call the collective ones in the same order. An error (a lost rank) is returned as
// IOError; the caller ends the whole run, since the other ranks may be waiting for this one.
// Thread-safety: one thread at a time (the caller's main thread).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"

namespace motif {

class RankGroup {
 public:
  virtual ~RankGroup() = default;

  virtual int rank() const = 0;
  virtual int size() const = 0;

  // Collective. `data` holds starts.back() elements of `element_bytes` bytes; rank r has filled
  // elements [starts[r], starts[r + 1]). Afterwards every rank holds every rank's part.
  virtual Status ShareParts(void* data, uint64_t element_bytes,
                            const std::vector<uint64_t>& starts) = 0;
  // Collective: rank 0's `bytes` replace every other rank's.
  virtual Status Broadcast(std::string* bytes) = 0;
  // Collective: rank 0's `values` become the element-wise sums over all ranks (the same length
  // on every rank); the others' are left as they were.
  virtual Status SumToRoot(std::vector<uint64_t>* values) = 0;
  // Collective: rank 0 gets every rank's `value` (index = rank); the others get an empty vector.
  virtual Result<std::vector<uint64_t>> GatherToRoot(uint64_t value) = 0;

  // Point to point, to rank 0 (not from it): queued, returns at once; at most a few messages
  // are in flight (the oldest is waited for beyond that). `tag` names the message.
  virtual Status SendToRoot(uint64_t tag, std::string bytes) = 0;
  // Rank 0: the message `tag` from `from` (waits for it).
  virtual Result<std::string> ReceiveFrom(int from, uint64_t tag) = 0;
  // Waits until every message this rank queued has been delivered.
  virtual Status FinishSends() = 0;

  // Bytes this rank has sent so far (every method above).
  virtual uint64_t bytes_sent() const = 0;
};

// starts (size parts + 1) of `parts` near-equal ranges of [0, count), each boundary a multiple
// of `align` (> 0) except the last, count.
std::vector<uint64_t> PartStarts(uint64_t count, int parts, uint64_t align);

// This rank's share of `count` items: one part per rank (PartStarts) and its own,
// [starts[own], starts[own + 1]). Without ranks, or with one: all of them, {0, count}.
struct RankShare {
  std::vector<uint64_t> starts;
  size_t own = 0;

  bool shared() const { return starts.size() > 2; }  // among several ranks
  uint64_t first() const { return starts[own]; }
  uint64_t end() const { return starts[own + 1]; }
};
RankShare ShareOf(uint64_t count, const RankGroup* ranks, uint64_t align = 1);

}  // namespace motif
