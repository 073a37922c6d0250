#include "engine/distributed/mpi_rank_group.h"

#include <chrono>
#include <climits>
#include <cstring>
#include <thread>

namespace motif {
namespace {

// The one tag of the blocks sent to rank 0 (their number travels in the message).
constexpr int kBlockTag = 1;
// Blocks a rank may have in flight to rank 0 before it waits for the oldest.
constexpr size_t kMaxSendsInFlight = 4;
// Broadcast pieces: MPI counts are int.
constexpr uint64_t kMaxPieceBytes = uint64_t{1} << 30;

// Tests, then sleeps between tests: a waiting rank leaves the CPU to the ranks it waits for.
void Pause(int* spins) {
  if (++*spins > 64) std::this_thread::sleep_for(std::chrono::microseconds(200));
}

Status Check(int code, const char* what) {
  if (code == MPI_SUCCESS) return Status::Ok();
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  return Status::IOError(std::string(what) + ": " + std::string(text, length));
}

Status WaitPatiently(MPI_Request* request, const char* what) {
  int done = 0;
  for (int spins = 0;;) {
    MOTIF_RETURN_IF_ERROR(Check(MPI_Test(request, &done, MPI_STATUS_IGNORE), what));
    if (done) return Status::Ok();
    Pause(&spins);
  }
}

}  // namespace

MpiRankGroup::MpiRankGroup(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  MPI_Comm node;
  MPI_Comm_split_type(comm_, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &node_size_);
  MPI_Comm_free(&node);
}

MpiRankGroup::~MpiRankGroup() { (void)FinishSends(); }

Status MpiRankGroup::BroadcastBytes(void* data, uint64_t bytes, int root) {
  auto* at = static_cast<char*>(data);
  for (uint64_t done = 0; done < bytes;) {
    const uint64_t piece = std::min(kMaxPieceBytes, bytes - done);
    MPI_Request request;
    MOTIF_RETURN_IF_ERROR(
        Check(MPI_Ibcast(at + done, static_cast<int>(piece), MPI_BYTE, root, comm_, &request),
              "MPI_Ibcast"));
    MOTIF_RETURN_IF_ERROR(WaitPatiently(&request, "MPI_Ibcast"));
    if (root == rank_) bytes_sent_ += piece * static_cast<uint64_t>(size_ - 1);
    done += piece;
  }
  return Status::Ok();
}

Status MpiRankGroup::ShareParts(void* data, uint64_t element_bytes,
                                const std::vector<uint64_t>& starts) {
  if (starts.size() != static_cast<size_t>(size_) + 1) {
    return Status::InvalidArgument("ShareParts: one part per rank");
  }
  for (int root = 0; root < size_; ++root) {
    const uint64_t first = starts[static_cast<size_t>(root)];
    const uint64_t end = starts[static_cast<size_t>(root) + 1];
    MOTIF_RETURN_IF_ERROR(BroadcastBytes(static_cast<char*>(data) + first * element_bytes,
                                         (end - first) * element_bytes, root));
  }
  return Status::Ok();
}

Status MpiRankGroup::Broadcast(std::string* bytes) {
  uint64_t size = bytes->size();
  MOTIF_RETURN_IF_ERROR(BroadcastBytes(&size, sizeof(size), 0));
  if (rank_ != 0) bytes->resize(size);
  return BroadcastBytes(bytes->data(), size, 0);
}

Status MpiRankGroup::SumToRoot(std::vector<uint64_t>* values) {
  MPI_Request request;
  const int count = static_cast<int>(values->size());
  MOTIF_RETURN_IF_ERROR(
      Check(MPI_Ireduce(rank_ == 0 ? MPI_IN_PLACE : values->data(), values->data(), count,
                        MPI_UINT64_T, MPI_SUM, 0, comm_, &request),
            "MPI_Ireduce"));
  if (rank_ != 0) bytes_sent_ += values->size() * sizeof(uint64_t);
  return WaitPatiently(&request, "MPI_Ireduce");
}

Result<std::vector<uint64_t>> MpiRankGroup::GatherToRoot(uint64_t value) {
  std::vector<uint64_t> values(rank_ == 0 ? static_cast<size_t>(size_) : 0);
  MPI_Request request;
  MOTIF_RETURN_IF_ERROR(Check(
      MPI_Igather(&value, 1, MPI_UINT64_T, values.data(), 1, MPI_UINT64_T, 0, comm_, &request),
      "MPI_Igather"));
  if (rank_ != 0) bytes_sent_ += sizeof(value);
  MOTIF_RETURN_IF_ERROR(WaitPatiently(&request, "MPI_Igather"));
  return values;
}

Status MpiRankGroup::SendToRoot(uint64_t tag, std::string bytes) {
  std::string message(sizeof(tag), '\0');
  std::memcpy(message.data(), &tag, sizeof(tag));
  message += bytes;
  if (message.size() > static_cast<uint64_t>(INT_MAX)) {
    return Status::NotSupported("a trellis block of more than 2 GiB cannot be sent");
  }
  // Completed sends first, then at most kMaxSendsInFlight left after this one.
  while (!sends_.empty()) {
    int done = 0;
    MOTIF_RETURN_IF_ERROR(
        Check(MPI_Test(&sends_.front().request, &done, MPI_STATUS_IGNORE), "MPI_Test"));
    if (!done && sends_.size() < kMaxSendsInFlight) break;
    if (!done) MOTIF_RETURN_IF_ERROR(WaitPatiently(&sends_.front().request, "MPI_Isend"));
    sends_.pop_front();
  }
  sends_.push_back({MPI_REQUEST_NULL, std::move(message)});
  PendingSend& send = sends_.back();
  MOTIF_RETURN_IF_ERROR(Check(MPI_Isend(send.bytes.data(), static_cast<int>(send.bytes.size()),
                                        MPI_BYTE, 0, kBlockTag, comm_, &send.request),
                              "MPI_Isend"));
  bytes_sent_ += send.bytes.size();
  return Status::Ok();
}

Result<std::string> MpiRankGroup::ReceiveFrom(int from, uint64_t tag) {
  MPI_Status status;
  int arrived = 0;
  for (int spins = 0;;) {
    MOTIF_RETURN_IF_ERROR(
        Check(MPI_Iprobe(from, kBlockTag, comm_, &arrived, &status), "MPI_Iprobe"));
    if (arrived) break;
    Pause(&spins);
  }
  int count = 0;
  MPI_Get_count(&status, MPI_BYTE, &count);
  std::string message(static_cast<size_t>(count), '\0');
  MOTIF_RETURN_IF_ERROR(
      Check(MPI_Recv(message.data(), count, MPI_BYTE, from, kBlockTag, comm_, MPI_STATUS_IGNORE),
            "MPI_Recv"));
  uint64_t got = UINT64_MAX;
  if (message.size() >= sizeof(got)) std::memcpy(&got, message.data(), sizeof(got));
  if (got != tag) {
    return Status::IOError("rank " + std::to_string(from) + " sent block " + std::to_string(got) +
                           " where block " + std::to_string(tag) + " was due");
  }
  return message.substr(sizeof(tag));
}

Status MpiRankGroup::FinishSends() {
  while (!sends_.empty()) {
    MOTIF_RETURN_IF_ERROR(WaitPatiently(&sends_.front().request, "MPI_Isend"));
    sends_.pop_front();
  }
  return Status::Ok();
}

}  // namespace motif
