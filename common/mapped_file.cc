#include "common/mapped_file.h"

#include <sys/mman.h>
#include <unistd.h>

#include <boost/interprocess/file_mapping.hpp>
#include <boost/interprocess/mapped_region.hpp>
#include <filesystem>
#include <system_error>

namespace motif {

struct MappedFile::Mapping {
  boost::interprocess::file_mapping file;
  boost::interprocess::mapped_region region;
};

Result<std::unique_ptr<MappedFile>> MappedFile::Open(const std::string& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) return Status::NotFound(path + ": no such file");
  if (!std::filesystem::is_regular_file(status)) {
    return Status::IOError(path + ": not a regular file");
  }
  const uint64_t size = std::filesystem::file_size(path, error);
  if (error) return Status::IOError(path + ": cannot read the size: " + error.message());
  std::unique_ptr<MappedFile> mapped(new MappedFile());
  mapped->path_ = path;
  if (size > 0) {
    try {
      namespace bip = boost::interprocess;
      bip::file_mapping file(path.c_str(), bip::read_only);
      bip::mapped_region region(file, bip::read_only);  // the whole file
      mapped->mapping_ = std::make_unique<Mapping>(Mapping{std::move(file), std::move(region)});
    } catch (const std::exception& exception) {
      return Status::IOError(path + ": cannot map: " + exception.what());
    }
    mapped->data_ = static_cast<const uint8_t*>(mapped->mapping_->region.get_address());
    mapped->size_ = mapped->mapping_->region.get_size();
    mapped->guard_ = std::make_unique<MappingGuard>(mapped->data_, mapped->size_);
  }
  return mapped;
}

MappedFile::~MappedFile() = default;

Status MappedFile::CheckNotCut() const {
  std::error_code error;
  const uint64_t now = std::filesystem::file_size(path_, error);
  if (!cut() && !error && now >= size_) return Status::Ok();
  const std::string now_text = error ? "no longer readable" : std::to_string(now) + " bytes";
  return Status::Corruption(path_ + ": the file was cut while it was being read: it was " +
                            std::to_string(size_) + " bytes when opened, now " + now_text);
}

Status MappedFile::ExplainRead(Status read) const {
  if (read.ok() && !cut()) return read;
  Status cut_status = CheckNotCut();
  return cut_status.ok() ? read : cut_status;
}

// posix_madvise (what boost's advice_dontneed calls) is a no-op in glibc: madvise is used.
uint64_t MappedFile::ReleasePages(uint64_t begin_offset, uint64_t end_offset) const {
  static const uint64_t page_bytes = static_cast<uint64_t>(::sysconf(_SC_PAGESIZE));
  const uint64_t begin = begin_offset / page_bytes * page_bytes;
  const uint64_t end = end_offset / page_bytes * page_bytes;
  if (end <= begin) return begin;
  ::madvise(const_cast<uint8_t*>(data_) + begin, end - begin, MADV_DONTNEED);  // best effort
  return end;
}

}  // namespace motif
