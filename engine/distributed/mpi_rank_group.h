// MpiRankGroup: RankGroup over MPI (Open MPI on Debian), for motifmine-mpi. Built only where
// CMake finds MPI. Waits never spin a core: a rank waiting for another (rank 0 for a block, a
// rank for a broadcast while rank 0 imports) tests its request and sleeps between tests, so
// ranks oversubscribed on fewer cores, and a rank's own search threads, keep the CPU.
// Broadcasts go in pieces of at most 1 GiB (MPI counts are int). Blocks to rank 0 carry their
// number first, checked on arrival (messages between two ranks arrive in the order sent).
// Thread-safety: one thread at a time; MPI is initialised with MPI_THREAD_FUNNELED.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "common/rank_group.h"

namespace motif {

class MpiRankGroup final : public RankGroup {
 public:
  // Over `comm` (MPI_COMM_WORLD), MPI initialised already.
  explicit MpiRankGroup(MPI_Comm comm);
  ~MpiRankGroup() override;

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  // The ranks of this group on this node (MPI_COMM_TYPE_SHARED), for the default thread count.
  int ranks_on_this_node() const { return node_size_; }

  Status ShareParts(void* data, uint64_t element_bytes,
                    const std::vector<uint64_t>& starts) override;
  Status Broadcast(std::string* bytes) override;
  Status SumToRoot(std::vector<uint64_t>* values) override;
  Result<std::vector<uint64_t>> GatherToRoot(uint64_t value) override;
  Status SendToRoot(uint64_t tag, std::string bytes) override;
  Result<std::string> ReceiveFrom(int from, uint64_t tag) override;
  Status FinishSends() override;
  uint64_t bytes_sent() const override { return bytes_sent_; }

 private:
  struct PendingSend {
    MPI_Request request;
    std::string bytes;  // kept alive until the send completes
  };
  Status BroadcastBytes(void* data, uint64_t bytes, int root);

  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
  int node_size_ = 1;
  uint64_t bytes_sent_ = 0;
  std::deque<PendingSend> sends_;
};

}  // namespace motif
