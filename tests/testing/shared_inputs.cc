#include "tests/testing/shared_inputs.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace motif::testing {
namespace {

namespace fs = std::filesystem;

std::string CacheRoot() {
  const char* overridden = std::getenv("MOTIF_TEST_CACHE_DIR");
  if (overridden && *overridden) return overridden;
  return MOTIF_TEST_CACHE_DIR;
}

}  // namespace

std::string ExecutableStamp(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return "missing";
  const long long ns =
      static_cast<long long>(info.st_mtim.tv_sec) * 1000000000LL + info.st_mtim.tv_nsec;
  return std::to_string(static_cast<long long>(info.st_size)) + "-" + std::to_string(ns);
}

std::string SharedInputs(const std::string& key,
                         const std::function<bool(const std::string&)>& make) {
  const fs::path folder = fs::path(CacheRoot()) / key;
  std::error_code error;
  if (fs::is_directory(folder, error)) return folder.string();
  fs::create_directories(folder.parent_path(), error);
  const fs::path building = folder.string() + ".making-" + std::to_string(::getpid());
  fs::remove_all(building, error);
  fs::create_directories(building, error);
  if (!make(building.string())) {
    fs::remove_all(building, error);
    return "";
  }
  // Whole or not at all; when another process was first, its folder stands and this one goes.
  fs::rename(building, folder, error);
  if (error) fs::remove_all(building, error);
  return folder.string();
}

}  // namespace motif::testing
