#include "tests/testing/tmpfs.h"

#include <sys/mount.h>
#include <sys/statvfs.h>

#include <filesystem>

namespace motif::testing {

Tmpfs::Tmpfs(const std::string& path) : path_(path) {
  std::filesystem::create_directories(path);
  mounted_ = ::mount("tmpfs", path.c_str(), "tmpfs", 0, "size=64m") == 0;
}

Tmpfs::~Tmpfs() {
  if (mounted_) ::umount2(path_.c_str(), MNT_DETACH);
}

bool Tmpfs::LeaveRoom(uint64_t room_bytes) {
  struct statvfs stats {};
  if (::statvfs(path_.c_str(), &stats) != 0) return false;
  const uint64_t used = (stats.f_blocks - stats.f_bfree) * stats.f_frsize;
  const std::string options = "size=" + std::to_string(used + room_bytes);
  return ::mount("tmpfs", path_.c_str(), "tmpfs", MS_REMOUNT, options.c_str()) == 0;
}

}  // namespace motif::testing
