#include "engine/report/motifs_archive_check.h"

#include <string>
#include <unordered_map>

namespace motif {

const ClipInfo* FindClip(const FrameFileReader& reader, const std::string& name) {
  for (const ClipInfo& clip : reader.clips()) {
    if (clip.name == name) return &clip;
  }
  return nullptr;
}

Status CheckMotifsMatchArchive(const MotifsDocument& document, const std::string& motifs_path,
                               const FrameFileReader& reader) {
  const std::string other = motifs_path + " was mined from another archive than " + reader.path() +
                            " (or another version of it): ";
  if (document.frames != reader.frame_count()) {
    return Status::InvalidArgument(other + "it has " + std::to_string(document.frames) +
                                   " frames, the archive " + std::to_string(reader.frame_count()));
  }
  // Archives can hold many thousands of clips: look names up in a map, not a scan per instance.
  std::unordered_map<std::string, const ClipInfo*> clips_by_name;
  for (const ClipInfo& clip : reader.clips()) clips_by_name.emplace(clip.name, &clip);
  auto find = [&](const std::string& name) -> const ClipInfo* {
    auto it = clips_by_name.find(name);
    return it == clips_by_name.end() ? nullptr : it->second;
  };
  for (const MotifsJsonClip& listed : document.clips) {
    const ClipInfo* clip = find(listed.name);
    if (clip == nullptr) {
      return Status::InvalidArgument(other + "the archive has no clip '" + listed.name + "'");
    }
    if (clip->frame_count != listed.frames || clip->first_frame != listed.first_frame) {
      return Status::InvalidArgument(
          other + "clip '" + listed.name + "' has " + std::to_string(listed.frames) +
          " frames from global frame " + std::to_string(listed.first_frame) + ", the archive's " +
          std::to_string(clip->frame_count) + " from " + std::to_string(clip->first_frame));
    }
  }
  for (const MotifsJsonMotif& motif : document.motifs) {
    for (const MotifsJsonInstance& instance : motif.instances) {
      const ClipInfo* clip = find(instance.clip);
      if (clip == nullptr || instance.end <= instance.start || instance.end > clip->frame_count) {
        return Status::InvalidArgument(
            other + "motif " + std::to_string(motif.id) + " has instance " + instance.clip + " [" +
            std::to_string(instance.start) + ", " + std::to_string(instance.end) +
            "), which is not inside a clip of the archive");
      }
    }
  }
  return Status::Ok();
}

}  // namespace motif
