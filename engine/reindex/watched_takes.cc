#include "engine/reindex/watched_takes.h"

#include <chrono>
#include <filesystem>
#include <unordered_map>
#include <unordered_set>

#include "common/byte_coding.h"

#include "common/file_util.h"

namespace motif {

namespace fs = std::filesystem;

std::string WatchedPath(const std::string& path) {
  std::error_code error;
  fs::path absolute = fs::absolute(path, error);
  if (error) absolute = path;
  return absolute.lexically_normal().string();
}

Result<WatchScan> ScanWatchedFolder(const std::string& dir, const std::vector<ClipInfo>& clips,
                                    const ImportOptions& options, double min_age_seconds) {
  std::error_code error;
  if (!fs::is_directory(dir, error)) {
    return Status::NotFound(dir + ": no such folder to watch (watch)").WithOption("watch");
  }
  MOTIF_ASSIGN_OR_RETURN(std::vector<TakeSource> sources,
                         DiscoverTakes({WatchedPath(dir)}, options));
  std::unordered_set<uint64_t> known_hashes;
  std::unordered_map<std::string, const ClipInfo*> by_source;
  for (const ClipInfo& clip : clips) {
    if (clip.content_hash != 0) known_hashes.insert(clip.content_hash);
    by_source.emplace(clip.source_path, &clip);
  }
  WatchScan scan;
  const auto now = fs::file_time_type::clock::now();
  for (TakeSource& source : sources) {
    source.path = WatchedPath(source.path);
    if (!source.asf_path.empty()) source.asf_path = WatchedPath(source.asf_path);
    const fs::file_time_type modified = fs::last_write_time(source.path, error);
    if (error) return Status::IOError(source.path + ": " + error.message());
    if (min_age_seconds > 0 &&
        std::chrono::duration<double>(now - modified).count() < min_age_seconds) {
      scan.settling.push_back(source.path);
      continue;
    }
    Result<std::string> read = ReadTakeFile(source.path);
    if (!read.ok() && read.status().IsInvalidArgument()) {
      scan.new_takes.push_back(source);  // refused by the import, take by take (--skip-bad)
      continue;
    }
    MOTIF_ASSIGN_OR_RETURN(std::string bytes, std::move(read));
    scan.scanned_bytes += bytes.size();
    const uint64_t hash = Checksum64(bytes.data(), bytes.size());
    if (known_hashes.count(hash)) {
      ++scan.known_takes;
      continue;
    }
    const auto imported = by_source.find(source.path);
    if (imported != by_source.end()) {
      scan.changed.push_back(source.path + ": changed since it was imported as clip '" +
                             imported->second->name +
                             "'; not imported again (give the new content another file name)");
      continue;
    }
    scan.new_takes.push_back(source);
  }
  return scan;
}

}  // namespace motif
