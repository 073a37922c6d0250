// BlockWriteQueue: a trellis build's writes, one block at a time on a writer thread, so that the
// search of the next block goes on while a block is compressed, written and fsynced. Blocks are
// written in the order they are started, so the file is the one a serial loop writes. Used by
// the single process's build (trellis_builder.cc) and by rank 0 of a distributed one
// (distributed_columns.cc).
// Thread-safety: one thread starts and waits; the writer is used only by the writer thread
// while a write is in flight.
#pragma once

#include <chrono>
#include <future>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "common/seconds_since.h"
#include "common/status.h"
#include "formats/trellis_file/trellis_file_writer.h"

namespace motif {

class BlockWriteQueue {
 public:
  explicit BlockWriteQueue(TrellisFileWriter* writer) : writer_(writer) {}
  ~BlockWriteQueue() {
    if (pending_.valid()) pending_.wait();  // never leave with a write in flight
  }
  BlockWriteQueue(const BlockWriteQueue&) = delete;
  BlockWriteQueue& operator=(const BlockWriteQueue&) = delete;

  // Waits for the write in flight, if any, adding the wait to *wait_seconds; its status.
  Status Wait(double* wait_seconds) {
    if (!pending_.valid()) return Status::Ok();
    const auto start = std::chrono::steady_clock::now();
    Status status = pending_.get();
    *wait_seconds += SecondsSince(start);
    return status;
  }
  // Start one write; the previous one must have been waited for.
  void StartColumns(std::vector<std::vector<Neighbour>> columns) {
    pending_ = std::async(std::launch::async, [this, columns = std::move(columns)] {
      return Timed([&] { return writer_->AppendBlock(columns); });
    });
  }
  void StartEncoded(std::string bytes) {
    pending_ = std::async(std::launch::async, [this, bytes = std::move(bytes)] {
      return Timed([&] {
        return writer_->AppendEncodedBlock(reinterpret_cast<const uint8_t*>(bytes.data()),
                                           bytes.size());
      });
    });
  }
  // The writer thread's time in the writes waited for so far.
  double write_seconds() const { return write_seconds_; }

 private:
  template <typename Write>
  Status Timed(Write write) {
    const auto start = std::chrono::steady_clock::now();
    Status status;
    try {
      status = write();
    } catch (const std::bad_alloc&) {
      status = Status::ResourceExhausted("trellis writer: out of memory");
    }
    write_seconds_ += SecondsSince(start);  // read only after Wait
    return status;
  }

  TrellisFileWriter* writer_;
  std::future<Status> pending_;
  double write_seconds_ = 0;
};

}  // namespace motif
