#include "engine/cli/mined_motifs.h"

#include <filesystem>

#include "engine/report/motifs_archive_check.h"

namespace motif::cli {

Result<MinedMotifs> OpenMinedMotifs(const std::string& dir, const std::string& archive_path) {
  MinedMotifs mined;
  mined.dir = dir;
  std::error_code error;
  mined.motifs_path = std::filesystem::is_regular_file(dir, error)
                          ? dir
                          : (std::filesystem::path(dir) / "motifs.json").string();
  if (!std::filesystem::exists(mined.motifs_path, error)) {
    return Status::NotFound(mined.motifs_path + " does not exist (`motifmine cluster ARCHIVE " +
                            "--out " + dir + "` writes it)");
  }
  MOTIF_ASSIGN_OR_RETURN(mined.document, ReadMotifsJson(mined.motifs_path));
  const std::string archive = archive_path.empty() ? mined.document.archive : archive_path;
  // The version mined, when motifs.json records it: later appends to the archive (a reindex
  // importing tonight's takes) do not change what this motifs.json describes.
  const MotifsArchiveVersion& version = mined.document.archive_version;
  Result<std::unique_ptr<FrameFileReader>> opened =
      version.known()
          ? FrameFileReader::OpenCommit(archive, version.generation, version.committed_bytes)
          : FrameFileReader::Open(archive);
  if (opened.ok() && version.known() && (*opened)->summary().identity != version.identity) {
    return Status::InvalidArgument(archive + ": its version " + std::to_string(version.generation) +
                                   " is not the one " + mined.motifs_path +
                                   " was mined from (another archive?)");
  }
  if (!opened.ok()) {
    if (opened.status().IsNotFound() && archive_path.empty()) {
      return Status::NotFound(opened.status().message() + " (the archive named in " +
                              mined.motifs_path + "; give its new path with --archive)");
    }
    return opened.status();
  }
  mined.archive = std::move(opened).value();
  MOTIF_RETURN_IF_ERROR(CheckMotifsMatchArchive(mined.document, mined.motifs_path, *mined.archive));
  return mined;
}

}  // namespace motif::cli
