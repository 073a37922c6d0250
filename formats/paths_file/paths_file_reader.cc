#include "formats/paths_file/paths_file_reader.h"

#include <zstd.h>

#include <filesystem>
#include <system_error>

#include "common/file_util.h"
#include "formats/paths_file/paths_file_format.h"

namespace motif {

struct PathsFileReader::Contents {
  std::string path;
  uint64_t file_bytes = 0;
  paths_file::FileHeader header;
  std::vector<PathCandidate> candidates;
};

namespace {

// Decompresses the records section: exactly one zstd frame of the declared content size.
Status DecompressRecords(const uint8_t* frame, size_t size, uint64_t raw_size, std::string* raw) {
  const unsigned long long content_size = ZSTD_getFrameContentSize(frame, size);
  if (content_size == ZSTD_CONTENTSIZE_ERROR || content_size == ZSTD_CONTENTSIZE_UNKNOWN ||
      content_size != raw_size) {
    return Status::Corruption("not a zstd frame of " + std::to_string(raw_size) + " bytes");
  }
  if (ZSTD_findFrameCompressedSize(frame, size) != size) {
    return Status::Corruption("not exactly one zstd frame");
  }
  raw->resize(raw_size);
  char dummy = 0;
  const size_t decoded = ZSTD_decompress(raw_size ? raw->data() : &dummy, raw_size, frame, size);
  if (ZSTD_isError(decoded) || decoded != raw_size) {
    return Status::Corruption(
        std::string("zstd frame does not decode") +
        (ZSTD_isError(decoded) ? std::string(": ") + ZSTD_getErrorName(decoded) : std::string()));
  }
  return Status::Ok();
}

}  // namespace

Result<std::unique_ptr<PathsFileReader>> PathsFileReader::FromBytes(const std::string& bytes,
                                                                    const std::string& name) {
  auto contents = std::make_unique<Contents>();
  contents->path = name;
  contents->file_bytes = bytes.size();
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  paths_file::FileHeader& header = contents->header;
  Status status = paths_file::FileHeader::DecodeFrom(data, bytes.size(), &header);
  if (!status.ok()) return status.WithContext(name);
  const uint8_t* section = data + header.header_bytes;
  const std::string where = name + ": records section at offset " + Hex(header.header_bytes);
  if (paths_file::Checksum64(section, header.records_bytes) != header.records_checksum) {
    return Status::Corruption(where + ": checksum mismatch");
  }
  std::string raw;
  status = DecompressRecords(section, header.records_bytes, header.records_raw_bytes, &raw);
  if (!status.ok()) return status.WithContext(where);
  status = paths_file::DecodeRecords(reinterpret_cast<const uint8_t*>(raw.data()), raw.size(),
                                     header.candidate_count, header.params, &contents->candidates);
  if (!status.ok()) return status.WithContext(where);
  return std::unique_ptr<PathsFileReader>(new PathsFileReader(std::move(contents)));
}

Result<std::unique_ptr<PathsFileReader>> PathsFileReader::Open(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(std::string bytes, ReadRegularFile(path));
  return FromBytes(bytes, path);
}

PathsFileReader::PathsFileReader(std::unique_ptr<Contents> contents)
    : contents_(std::move(contents)) {}
PathsFileReader::~PathsFileReader() = default;

const PathsParams& PathsFileReader::params() const { return contents_->header.params; }
const std::vector<PathCandidate>& PathsFileReader::candidates() const {
  return contents_->candidates;
}
const std::string& PathsFileReader::path() const { return contents_->path; }
uint64_t PathsFileReader::file_bytes() const { return contents_->file_bytes; }
uint16_t PathsFileReader::format_minor() const { return contents_->header.format_minor; }

}  // namespace motif
