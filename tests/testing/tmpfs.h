// Tmpfs: a small tmpfs mounted for one test (root only; mounted() says whether it worked), and
// unmounted when the object goes out of scope. Tests of a full disk fill it for real.
#pragma once

#include <cstdint>
#include <string>

namespace motif::testing {

class Tmpfs {
 public:
  explicit Tmpfs(const std::string& path);  // 64 MB at `path`, created if missing
  ~Tmpfs();
  Tmpfs(const Tmpfs&) = delete;
  Tmpfs& operator=(const Tmpfs&) = delete;

  bool mounted() const { return mounted_; }
  // Resizes it to what is used now plus `room_bytes` (rounded up to pages by the kernel).
  bool LeaveRoom(uint64_t room_bytes);

 private:
  std::string path_;
  bool mounted_ = false;
};

}  // namespace motif::testing
