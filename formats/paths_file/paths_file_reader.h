// PathsFileReader: opens a paths file (.mpa, docs/formats/paths_file.md), checks every byte of
// it (header checksum, records checksum, the zstd frame, every record against the header's
// params and the sort order) and holds its candidates in memory. The whole file is validated
// by Open: a file that opens is entirely intact.
// Thread-safety: const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/status.h"
#include "formats/paths_file/path_candidate.h"
#include "formats/paths_file/paths_file_writer.h"

namespace motif {

class PathsFileReader {
 public:
  // NotFound (no file); IOError (cannot read it); Corruption (empty or short file, bad magic,
  // another major version, a checksum, a size that does not add up, a record out of range or
  // out of order), the message naming the file and the offset.
  static Result<std::unique_ptr<PathsFileReader>> Open(const std::string& path);
  // The same checks on bytes in memory; `name` stands for the file in messages.
  static Result<std::unique_ptr<PathsFileReader>> FromBytes(const std::string& bytes,
                                                            const std::string& name);
  ~PathsFileReader();

  const PathsParams& params() const;
  // Sorted by (top_start, match_start, top_end, match_end, root_column, root_frame).
  const std::vector<PathCandidate>& candidates() const;
  const std::string& path() const;
  uint64_t file_bytes() const;
  uint16_t format_minor() const;  // of the writer (this reader reads any 1.x)

 private:
  struct Contents;
  explicit PathsFileReader(std::unique_ptr<Contents> contents);
  std::unique_ptr<Contents> contents_;
};

}  // namespace motif
