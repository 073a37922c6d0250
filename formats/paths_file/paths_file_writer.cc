#include "formats/paths_file/paths_file_writer.h"

#include <zstd.h>

#include "common/file_util.h"
#include "formats/paths_file/paths_file_format.h"

namespace motif {

Result<std::string> EncodePathsFile(const PathsParams& params,
                                    const std::vector<PathCandidate>& candidates, int zstd_level) {
  std::string problem = paths_file::ParamsProblem(params);
  if (problem.empty()) problem = paths_file::CandidatesProblem(params, candidates);
  if (!problem.empty()) return Status::InvalidArgument("paths file: " + problem);
  if (zstd_level < ZSTD_minCLevel() || zstd_level > ZSTD_maxCLevel()) {
    return Status::InvalidArgument("paths file: zstd level " + std::to_string(zstd_level));
  }
  std::string raw;
  paths_file::EncodeRecords(params, candidates, &raw);
  std::string compressed(ZSTD_compressBound(raw.size()), '\0');
  // One frame that declares its content size (ZSTD_compress always does).
  const size_t compressed_size =
      ZSTD_compress(compressed.data(), compressed.size(), raw.data(), raw.size(), zstd_level);
  if (ZSTD_isError(compressed_size)) {
    return Status::IOError(std::string("paths file: zstd compression failed: ") +
                           ZSTD_getErrorName(compressed_size));
  }
  compressed.resize(compressed_size);

  paths_file::FileHeader header;
  header.params = params;
  header.candidate_count = candidates.size();
  header.records_raw_bytes = raw.size();
  header.records_bytes = compressed.size();
  header.records_checksum = paths_file::Checksum64(compressed.data(), compressed.size());
  std::string bytes;
  header.EncodeTo(&bytes);
  bytes += compressed;
  return bytes;
}

Status WritePathsFile(const std::string& path, const PathsParams& params,
                      const std::vector<PathCandidate>& candidates,
                      const PathsFileWriterOptions& options) {
  Result<std::string> bytes = EncodePathsFile(params, candidates, options.zstd_level);
  if (!bytes.ok()) return bytes.status().WithContext(path);
  if (options.file_system == nullptr) return Status::InvalidArgument(path + ": no file system");
  return AtomicWriteFile(path, *bytes, options.file_system);
}

}  // namespace motif
