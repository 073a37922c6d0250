// TrellisFileWriter: writes the matching trellis (docs/formats/trellis_file.md) as it is built,
// one column block at a time, so the builder never holds more than a block of columns: peak
// memory is one encoded block plus the block index (N / block_columns entries of 40 bytes),
// never O(N * K).
//
// Resumable: blocks go to "<path>.partial", whose header holds the params, and each block carries
// its own column range and checksum; each block is durable (written and fsynced) once AppendBlock
// returns. If a build is interrupted, OpenOrResume on the same path with the same TrellisParams
// and block_columns scans the blocks already there (verifying each one's checksum, dropping a
// torn or damaged tail) and next_column() says where to continue. Finish() writes the block index
// and footer, syncs, and renames "<path>.partial" to `path` atomically (then syncs the
// directory); a reader never sees a half-written trellis. Parameters that differ from those of a
// partial file start a fresh build (the stale partial file is replaced). An existing finished
// file at `path` does not stop a build: it is replaced when the new one finishes (callers that
// want to reuse it read its params with TrellisFileReader first).
// After an I/O error the writer is closed (every later call returns that error) and the partial
// file is left for a later OpenOrResume. Only one writer may build a path at a time: a second
// gets Busy ("locked").
// Thread-safety: one thread at a time.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/status.h"
#include "common/writable_file.h"
#include "formats/trellis_file/trellis_column.h"
#include "formats/trellis_file/trellis_params.h"

namespace motif {

struct TrellisFileWriterOptions {
  uint32_t block_columns = 4096;
  int zstd_level = 3;
  FileSystem* file_system = PosixFileSystem();
  // fsync after every block, so that an interrupted build resumes after the last block written
  // even after a power loss. false: only Finish syncs (before its rename); a build killed, not
  // powered off, still resumes where it was (the page cache keeps what was written), and one
  // cut by a power loss resumes after the last block that reached the disk (each block checks
  // itself). For writers that write much faster than the disk syncs (an incremental update).
  bool sync_each_block = true;
};

class TrellisFileWriter {
 public:
  // Starts a new build of `path`, or resumes "<path>.partial" if it holds blocks written with
  // equal params and block size. InvalidArgument: params (eps not finite and > 0, frame_count
  // above 2^32, k_max 0, search_params over 64 KiB) or options (block_columns not in [1, 2^20],
  // zstd level, no file system). Busy ("locked" if another writer builds the same path);
  // IOError / ResourceExhausted from the file system.
  static Result<std::unique_ptr<TrellisFileWriter>> OpenOrResume(
      const std::string& path, const TrellisParams& params,
      const TrellisFileWriterOptions& options = {});
  ~TrellisFileWriter();  // without Finish(): leaves the partial file for a later resume

  // "<path>.partial": where a build of `path` writes until Finish().
  static std::string PartialPath(const std::string& path);

  // First column not yet written: 0 for a new build, a multiple of block_columns on resume.
  uint64_t next_column() const;
  uint32_t block_columns() const;

  // Appends the block of columns [next_column(), next_column() + columns.size()); the size must
  // be block_columns except for the last block. Each column: at most k_max neighbours, frames
  // strictly increasing and below frame_count, distances in [0, eps]; a block holds at most
  // 2^28 neighbours. InvalidArgument if not (the writer is unchanged); IOError /
  // ResourceExhausted on write failure. Durable (fsynced) when it returns OK, with
  // sync_each_block.
  Status AppendBlock(const std::vector<std::vector<Neighbour>>& columns);

  // Appends a block already encoded (`size` bytes: header, sections, trailer), such as an
  // unchanged block of another trellis read with TrellisFileReader::ReadEncodedBlock or one
  // made by trellis_file::BlockEncoder, without decoding it: an incremental update copies the
  // blocks it does not change. Checked: the framing and the trailer checksum, that the block
  // holds columns [next_column(), next_column() + block size) and at most k_max neighbours a
  // column on average (InvalidArgument, the writer unchanged). The caller guarantees what only a
  // decode would show: it was encoded with this file's eps, and its frames are below
  // frame_count and at most k_max a column. IOError / ResourceExhausted as AppendBlock.
  Status AppendEncodedBlock(const uint8_t* bytes, uint64_t size);

  // After all frame_count columns: index, footer, sync, rename into place, sync the directory.
  // InvalidArgument before all columns are written. The writer is closed afterwards.
  Status Finish();

 private:
  class Impl;
  explicit TrellisFileWriter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace motif
