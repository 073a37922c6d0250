// motifmine::Archive and motifmine::ImportTakes (include/motifmine/archive.h) over the engine's
// FrameFileReader and ImportIntoArchive.
#include <utility>

#include "engine/api/archive_impl.h"
#include "engine/api/public_status.h"
#include "engine/ingest/archive_import.h"
#include "motifmine/archive.h"

namespace motifmine {

Status Archive::Impl::FindClip(const std::string& clip, const motif::ClipInfo** info) const {
  for (const motif::ClipInfo& candidate : reader->clips()) {
    if (candidate.name == clip) *info = &candidate;
  }
  if (*info == nullptr) {
    return {Status::Code::kNotFound, reader->path() + ": no clip named '" + clip + "'"};
  }
  return {};
}

Status Archive::Impl::FindRange(const std::string& clip, uint64_t start, uint64_t end,
                                const motif::ClipInfo** info) const {
  *info = nullptr;
  if (Status found = FindClip(clip, info); !found.ok()) return found;
  if (start > end || end > (*info)->frame_count) {
    return {Status::Code::kInvalidArgument, "start and end: frames [" + std::to_string(start) +
                                                ", " + std::to_string(end) + ") are not in clip '" +
                                                clip + "' of " +
                                                std::to_string((*info)->frame_count) + " frames"};
  }
  return {};
}

Archive::Archive(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Archive::~Archive() = default;

Status Archive::Open(const std::string& path, std::unique_ptr<Archive>* archive) {
  motif::Result<std::unique_ptr<motif::FrameFileReader>> reader =
      motif::FrameFileReader::Open(path);
  if (!reader.ok()) return motif::ToPublicStatus(reader.status());
  auto impl = std::make_unique<Impl>();
  impl->reader = std::move(*reader);
  for (const motif::ClipInfo& clip : impl->reader->clips()) {
    impl->clips.push_back(
        {clip.name, clip.source_path, clip.first_frame, clip.frame_count, clip.fps});
  }
  archive->reset(new Archive(std::move(impl)));
  return {};
}

const std::string& Archive::path() const { return impl_->reader->path(); }
uint64_t Archive::frames() const { return impl_->reader->frame_count(); }
double Archive::fps() const { return impl_->reader->fps(); }
const std::vector<Clip>& Archive::clips() const { return impl_->clips; }

std::vector<std::string> Archive::joint_names() const {
  std::vector<std::string> names;
  for (const motif::Joint& joint : impl_->reader->skeleton().joints()) names.push_back(joint.name);
  return names;
}

Status Archive::Rotations(const std::string& clip, uint64_t start, uint64_t end,
                          std::vector<float>* rotations) const {
  const motif::ClipInfo* found = nullptr;
  if (Status in_clip = impl_->FindRange(clip, start, end, &found); !in_clip.ok()) return in_clip;
  std::vector<float> rows;
  motif::Status read = impl_->reader->ReadFrames(found->first_frame + start, end - start, &rows);
  if (!read.ok()) return motif::ToPublicStatus(read);
  const motif::FrameLayout layout = impl_->reader->layout();
  rotations->resize((end - start) * layout.joint_count * 4);
  float* out = rotations->data();
  for (uint64_t frame = 0; frame < end - start; ++frame) {
    const float* row = rows.data() + frame * layout.stride();
    for (uint32_t joint = 0; joint < layout.joint_count; ++joint) {
      for (int c = 0; c < 4; ++c) *out++ = row[layout.quaternion_offset(joint) + c];
    }
  }
  return {};
}

Status ImportTakes(const std::string& archive_path, const std::vector<std::string>& paths,
                   const ImportOptions& options, ImportResult* result) {
  if (result == nullptr) return {Status::Code::kInvalidArgument, "no ImportResult to fill"};
  if (options.threads < 0) return {Status::Code::kInvalidArgument, "threads must be >= 0"};
  motif::ArchiveImportOptions import;
  import.skip_bad = options.skip_bad;
  import.threads = options.threads;
  motif::Result<motif::ArchiveImportResult> imported =
      motif::ImportIntoArchive(archive_path, paths, import);
  if (!imported.ok()) return motif::ToPublicStatus(imported.status());
  *result = ImportResult();
  result->takes_imported = imported->takes_imported;
  result->takes_already_present = imported->takes_already_present;
  result->takes_mapped = imported->takes_mapped;
  result->frames_added = imported->frames_added;
  result->skipped = imported->failures;
  return {};
}

}  // namespace motifmine
