#include "tests/testing/fault_injection.h"

namespace motif::testing {
namespace {

class FaultInjectingFile final : public WritableFile {
 public:
  FaultInjectingFile(FaultInjectingFileSystem* owner, std::unique_ptr<WritableFile> base)
      : owner_(owner), base_(std::move(base)) {}

  Status WriteAt(uint64_t offset, const void* data, size_t size) override {
    Status status = owner_->Step("write");
    if (!status.ok()) {
      // The torn part that reached the disk; the injected fault is what the writer must see.
      (void)base_->WriteAt(offset, data, size / 2);
      return status;
    }
    return base_->WriteAt(offset, data, size);
  }
  Status Sync() override {
    MOTIF_RETURN_IF_ERROR(owner_->Step("fsync"));
    return base_->Sync();
  }
  Status Truncate(uint64_t size) override {
    MOTIF_RETURN_IF_ERROR(owner_->Step("truncate"));
    return base_->Truncate(size);
  }
  Result<uint64_t> Size() override { return base_->Size(); }
  Status Close() override { return base_->Close(); }
  const std::string& path() const override { return base_->path(); }

 private:
  FaultInjectingFileSystem* owner_;
  std::unique_ptr<WritableFile> base_;
};

}  // namespace

Status FaultInjectingFileSystem::Step(const std::string& what) {
  const int64_t step = steps_++;
  if (fail_at_ >= 0 && (step == fail_at_ || (sticky_ && step > fail_at_))) {
    injected_ = true;
    return Status::ResourceExhausted("injected failure of " + what + " at step " +
                                     std::to_string(step) + " (No space left on device)");
  }
  return Status::Ok();
}

Result<std::unique_ptr<WritableFile>> FaultInjectingFileSystem::OpenWritable(
    const std::string& path, OpenMode mode) {
  MOTIF_RETURN_IF_ERROR(Step("open " + path));
  MOTIF_ASSIGN_OR_RETURN(auto file, base_->OpenWritable(path, mode));
  return std::unique_ptr<WritableFile>(new FaultInjectingFile(this, std::move(file)));
}

Status FaultInjectingFileSystem::Rename(const std::string& from, const std::string& to) {
  MOTIF_RETURN_IF_ERROR(Step("rename"));
  return base_->Rename(from, to);
}

Status FaultInjectingFileSystem::SyncParentDir(const std::string& path) {
  MOTIF_RETURN_IF_ERROR(Step("fsync directory"));
  return base_->SyncParentDir(path);
}

Status FaultInjectingFileSystem::Remove(const std::string& path) {
  MOTIF_RETURN_IF_ERROR(Step("remove"));
  return base_->Remove(path);
}

}  // namespace motif::testing
