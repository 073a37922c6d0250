#include "common/file_util.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <system_error>

#include "common/temporary_files.h"

namespace motif {

Result<std::string> ReadFileToString(const std::string& path, uint64_t max_bytes) {
  // Opened without blocking and checked on the open descriptor: a FIFO named as a file would
  // block the open until a writer came, and a device (/dev/zero) would be read without end.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return Status::NotFound(path + ": no such file");
    return Status::IOError(path + ": cannot open for reading: " + std::strerror(errno));
  }
  std::string bytes;
  Status status = [&]() -> Status {
    struct stat info {};
    if (::fstat(fd, &info) != 0) {
      return Status::IOError(path + ": cannot stat: " + std::strerror(errno));
    }
    if (S_ISDIR(info.st_mode))
      return Status::InvalidArgument(path + ": is a directory, not a file");
    if (!S_ISREG(info.st_mode)) {
      return Status::InvalidArgument(path + ": not a regular file (a FIFO, device or socket)");
    }
    const auto too_large = [&](uint64_t size) {
      return Status::InvalidArgument(path + ": " + std::to_string(size) + " bytes, more than the " +
                                     std::to_string(max_bytes) + " allowed for this file");
    };
    if (static_cast<uint64_t>(info.st_size) > max_bytes) return too_large(info.st_size);
    bytes.resize(static_cast<size_t>(info.st_size));
    size_t done = 0;
    for (;;) {
      if (done == bytes.size()) {
        // The size the stat gave is read: look for more through a small buffer first, so that
        // the usual end of file does not grow (and copy) the whole string.
        char probe[4096];
        const ssize_t more = ::read(fd, probe, sizeof probe);
        if (more < 0 && errno == EINTR) continue;
        if (more < 0) return Status::IOError(path + ": read failed: " + std::strerror(errno));
        if (more == 0) break;
        if (done + static_cast<uint64_t>(more) > max_bytes) return too_large(done + more);
        bytes.append(probe, static_cast<size_t>(more));  // it grew since the stat
        done += static_cast<size_t>(more);
        bytes.resize(static_cast<size_t>(std::min<uint64_t>(done + 65536, max_bytes)));
        if (done == bytes.size()) continue;  // at the limit: only an end of file may follow
      }
      const ssize_t got = ::read(fd, bytes.data() + done, bytes.size() - done);
      if (got < 0 && errno == EINTR) continue;
      if (got < 0) return Status::IOError(path + ": read failed: " + std::strerror(errno));
      if (got == 0) break;
      done += static_cast<size_t>(got);
    }
    if (done > max_bytes) return too_large(done);
    bytes.resize(done);
    return Status::Ok();
  }();
  ::close(fd);
  if (!status.ok()) return status;
  return bytes;
}

Result<std::string> ReadRegularFile(const std::string& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) return Status::NotFound(path + ": no such file");
  if (!std::filesystem::is_regular_file(status)) {
    return Status::IOError(path + ": not a regular file");
  }
  return ReadFileToString(path);
}

std::string TemporaryPathFor(const std::string& path) {
  static std::atomic<uint64_t> counter{0};
  std::string temp = path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  TrackTemporaryFile(temp);
  return temp;
}

Status AtomicWriteFile(const std::string& path, std::string_view content, FileSystem* file_system) {
  // A missing folder is named as such, not through the temporary file that could not be made.
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::error_code error;
  if (!folder.empty() && !std::filesystem::is_directory(folder, error)) {
    return Status::IOError(
        "cannot write " + path + ": " + folder.string() +
        (std::filesystem::exists(folder, error) ? " is not a folder" : " does not exist"));
  }
  const std::string temp_path = TemporaryPathFor(path);
  Status status = [&]() -> Status {
    MOTIF_ASSIGN_OR_RETURN(auto file,
                           file_system->OpenWritable(temp_path, OpenMode::kCreateExclusive));
    MOTIF_RETURN_IF_ERROR(file->WriteAt(0, content.data(), content.size()));
    MOTIF_RETURN_IF_ERROR(file->Sync());
    MOTIF_RETURN_IF_ERROR(file->Close());
    MOTIF_RETURN_IF_ERROR(file_system->Rename(temp_path, path));
    return file_system->SyncParentDir(path);
  }();
  // Best effort: the error that matters is `status`; a leftover temporary is removed later.
  if (!status.ok()) (void)file_system->Remove(temp_path);
  return status;
}

void RemoveStaleTemporaries(const std::string& dir, const std::vector<std::string>& names) {
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
    const std::string name = entry.path().filename().string();
    for (const std::string& owned : names) {
      const std::string prefix = owned + ".tmp-";
      if (name.compare(0, prefix.size(), prefix) != 0) continue;
      char* end = nullptr;
      const long pid = std::strtol(name.c_str() + prefix.size(), &end, 10);
      if (pid <= 0 || end == name.c_str() + prefix.size() || *end != '-') break;
      if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
        std::error_code ignored;
        std::filesystem::remove(entry.path(), ignored);
      }
      break;
    }
  }
}

}  // namespace motif
