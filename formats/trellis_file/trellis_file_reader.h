// TrellisFileReader: opens a finished trellis file (docs/formats/trellis_file.md), memory-mapped,
// validated from its footer (footer, header and params, block index: every structure's checksum
// and every index entry's place), and hands out columns: a block at a time in order (the path
// grower streams through them holding one block), or any column range (clustering reads
// instance pairs back). Each block's checksum is verified when it is read. Distances come back
// dequantised: within eps / 131070 + eps * 2^-24 of the written ones, exact for 0 and eps.
// Thread-safety: const methods are safe from many threads (each thread decodes with its own
// scratch).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/status.h"
#include "formats/trellis_file/trellis_block.h"
#include "formats/trellis_file/trellis_column.h"
#include "formats/trellis_file/trellis_file_writer.h"

namespace motif {

class TrellisFileReader {
 public:
  // NotFound; IOError (cannot open or map); Corruption (empty or short file, bad magic,
  // unsupported major version, any checksum, an index entry outside the file or out of order,
  // column ranges that do not tile [0, frame_count)), naming the file and the offset.
  static Result<std::unique_ptr<TrellisFileReader>> Open(const std::string& path);
  ~TrellisFileReader();

  const TrellisParams& params() const;
  uint64_t column_count() const;
  uint32_t block_columns() const;
  uint64_t block_count() const;
  uint64_t neighbour_count() const;  // total entries
  uint64_t file_bytes() const;
  const std::string& path() const;
  uint16_t format_minor() const;  // of the writer (this reader reads any 1.x)
  // Identifies this trellis's content: the footer checksum, which covers the header checksum
  // (the params) and the index checksum (every block's checksum). Results derived from the
  // trellis (the paths file) record it, and are rebuilt when it changes.
  uint64_t identity() const;

  // Decodes block `block_idx` (checksum verified) into *block (its vectors are reused). Without
  // `decode_distances` the distances are left 0 (the path grower needs only frames; about half
  // the decoding time). InvalidArgument if block_idx >= block_count(); Corruption naming the
  // file, block and offset.
  Status ReadBlock(uint64_t block_idx, TrellisBlock* block, bool decode_distances = true) const;
  // The bytes of block `block_idx` as stored (header, sections, trailer), valid while the
  // reader is open, after checking its trailer against its bytes and its index entry: what
  // TrellisFileWriter::AppendEncodedBlock copies into another trellis without decoding.
  // InvalidArgument if block_idx >= block_count(); Corruption naming the file, block and offset.
  Status ReadEncodedBlock(uint64_t block_idx, const uint8_t** bytes, uint64_t* size) const;
  // Columns [first, first + count) into *columns (resized to count). InvalidArgument if the
  // range is outside [0, column_count()); Corruption as ReadBlock.
  Status ReadColumns(uint64_t first_column, uint64_t count,
                     std::vector<std::vector<Neighbour>>* columns) const;
  // Gives the mapped pages of blocks [first_block, end_block) back to the kernel
  // (madvise(MADV_DONTNEED) on the read-only mapping: the file and the page cache are untouched,
  // a later read maps the pages again). For a sequential consumer such as the path grower: after
  // each block it has finished with, so that streaming through a trellis larger than memory does
  // not keep the file in the process's resident set. A page shared with the next block is kept
  // (released with that block). Safe beside concurrent reads of any block (they only fault the
  // pages back in). InvalidArgument unless first_block <= end_block <= block_count().
  Status ReleaseBlocks(uint64_t first_block, uint64_t end_block) const;
  // Every block's checksum and decoding, in file order; the pages of checked blocks are given
  // back to the kernel so a large file does not stay resident.
  Status Verify() const;

 private:
  class Impl;
  explicit TrellisFileReader(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace motif
