#include "common/writable_file.h"

#include <fcntl.h>
#include <stdio.h>  // renameat2, RENAME_NOREPLACE (glibc)
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>

#include "common/temporary_files.h"

namespace motif {
namespace {

class PosixWritableFile final : public WritableFile {
 public:
  PosixWritableFile(std::string path, int fd) : path_(std::move(path)), fd_(fd) {}
  // A destructor cannot report: writers that care Close() (and Sync()) before, and check it.
  ~PosixWritableFile() override { (void)Close(); }

  Status WriteAt(uint64_t offset, const void* data, size_t size) override {
    const char* bytes = static_cast<const char*>(data);
    while (size > 0) {
      ssize_t written = ::pwrite(fd_, bytes, size, static_cast<off_t>(offset));
      if (written < 0) {
        if (errno == EINTR) continue;
        return Status::FromErrno(path_ + ": write at offset " + std::to_string(offset), errno);
      }
      bytes += written;
      offset += static_cast<uint64_t>(written);
      size -= static_cast<size_t>(written);
    }
    return Status::Ok();
  }
  Status Sync() override {
    if (::fsync(fd_) != 0) return Status::FromErrno(path_ + ": fsync", errno);
    return Status::Ok();
  }
  Status Truncate(uint64_t size) override {
    if (::ftruncate(fd_, static_cast<off_t>(size)) != 0) {
      return Status::FromErrno(path_ + ": truncate to " + std::to_string(size) + " bytes", errno);
    }
    return Status::Ok();
  }
  Result<uint64_t> Size() override {
    struct stat st;
    if (::fstat(fd_, &st) != 0) return Status::FromErrno(path_ + ": stat", errno);
    return static_cast<uint64_t>(st.st_size);
  }
  Status Close() override {
    if (fd_ < 0) return Status::Ok();
    int rc = ::close(fd_);
    fd_ = -1;
    if (rc != 0) return Status::FromErrno(path_ + ": close", errno);
    return Status::Ok();
  }
  const std::string& path() const override { return path_; }

 private:
  std::string path_;
  int fd_;
};

class RealFileSystem final : public FileSystem {
 public:
  Result<std::unique_ptr<WritableFile>> OpenWritable(const std::string& path,
                                                     OpenMode mode) override {
    int flags = O_RDWR | O_CLOEXEC;
    if (mode == OpenMode::kCreateExclusive) flags |= O_CREAT | O_EXCL;
    int fd = ::open(path.c_str(), flags, 0644);
    if (fd < 0) return Status::FromErrno(path + ": open for writing", errno);
    return std::unique_ptr<WritableFile>(new PosixWritableFile(path, fd));
  }
  Status Rename(const std::string& from, const std::string& to) override {
    if (::rename(from.c_str(), to.c_str()) != 0) {
      return Status::FromErrno("rename " + from + " to " + to, errno);
    }
    UntrackTemporaryFile(from);  // in place: a signal now must not remove it
    return Status::Ok();
  }
  Status RenameNoReplace(const std::string& from, const std::string& to) override {
    if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) != 0) {
      if (errno == EEXIST) return Status::Busy(to + ": exists; not replaced");
      if (errno != EINVAL && errno != ENOSYS) {
        return Status::FromErrno("rename " + from + " to " + to, errno);
      }
      return FileSystem::RenameNoReplace(from, to);  // a file system without the flag
    }
    UntrackTemporaryFile(from);
    return Status::Ok();
  }
  Status SyncParentDir(const std::string& path) override {
    std::filesystem::path parent = std::filesystem::path(path).parent_path();
    if (parent.empty()) parent = ".";
    int fd = ::open(parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return Status::FromErrno(parent.string() + ": open directory", errno);
    int rc = ::fsync(fd);
    int saved_errno = errno;
    ::close(fd);
    if (rc != 0) return Status::FromErrno(parent.string() + ": fsync directory", saved_errno);
    return Status::Ok();
  }
  Status Remove(const std::string& path) override {
    if (::unlink(path.c_str()) != 0 && errno != ENOENT) {
      return Status::FromErrno(path + ": remove", errno);
    }
    UntrackTemporaryFile(path);
    return Status::Ok();
  }
};

}  // namespace

Status FileSystem::RenameNoReplace(const std::string& from, const std::string& to) {
  std::error_code error;
  if (std::filesystem::exists(to, error)) return Status::Busy(to + ": exists; not replaced");
  return Rename(from, to);
}

FileSystem* PosixFileSystem() {
  static RealFileSystem* file_system = new RealFileSystem();
  return file_system;
}

namespace {

class NoSyncFile final : public WritableFile {
 public:
  explicit NoSyncFile(std::unique_ptr<WritableFile> base) : base_(std::move(base)) {}
  Status WriteAt(uint64_t offset, const void* data, size_t size) override {
    return base_->WriteAt(offset, data, size);
  }
  Status Sync() override { return Status::Ok(); }
  Status Truncate(uint64_t size) override { return base_->Truncate(size); }
  Result<uint64_t> Size() override { return base_->Size(); }
  Status Close() override { return base_->Close(); }
  const std::string& path() const override { return base_->path(); }

 private:
  std::unique_ptr<WritableFile> base_;
};

class NoSyncFileSystemImpl final : public FileSystem {
 public:
  Result<std::unique_ptr<WritableFile>> OpenWritable(const std::string& path,
                                                     OpenMode mode) override {
    MOTIF_ASSIGN_OR_RETURN(auto file, PosixFileSystem()->OpenWritable(path, mode));
    return std::unique_ptr<WritableFile>(new NoSyncFile(std::move(file)));
  }
  Status Rename(const std::string& from, const std::string& to) override {
    return PosixFileSystem()->Rename(from, to);
  }
  Status RenameNoReplace(const std::string& from, const std::string& to) override {
    return PosixFileSystem()->RenameNoReplace(from, to);
  }
  Status SyncParentDir(const std::string&) override { return Status::Ok(); }
  Status Remove(const std::string& path) override { return PosixFileSystem()->Remove(path); }
};

}  // namespace

FileSystem* NoSyncFileSystem() {
  static NoSyncFileSystemImpl* file_system = new NoSyncFileSystemImpl();
  return file_system;
}

}  // namespace motif
