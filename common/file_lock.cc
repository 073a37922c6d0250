#include "common/file_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>

namespace motif {

Status ExclusiveFileLock::Acquire(const std::string& path, const std::string& held_message,
                                  bool create) {
  Release();
  const int fd = create ? ::open(path.c_str(), O_RDONLY | O_CREAT | O_CLOEXEC, 0644)
                        : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return Status::FromErrno(path + ": open to lock", errno);
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int saved_errno = errno;
    ::close(fd);
    if (saved_errno == EWOULDBLOCK) return Status::Busy(path + ": " + held_message);
    return Status::FromErrno(path + ": flock", saved_errno);
  }
  fd_ = fd;
  return Status::Ok();
}

void ExclusiveFileLock::Release() {
  if (fd_ >= 0) ::close(fd_);  // closing the descriptor releases the flock
  fd_ = -1;
}

}  // namespace motif
