#include "engine/reindex/mined_version.h"

#include <filesystem>

#include "common/byte_coding.h"
#include "common/file_util.h"

namespace motif {
namespace {

namespace fs = std::filesystem;

std::string InOutDir(const std::string& dir, const std::string& name) {
  return (fs::path(dir) / name).string();
}

// The file's bytes, checked against the manifest's size and checksum.
Result<std::string> ReadChecked(const std::string& out_dir, const VersionFile& file) {
  const std::string path = InOutDir(out_dir, file.path);
  MOTIF_ASSIGN_OR_RETURN(std::string bytes, ReadFileToString(path));
  if (bytes.size() != file.bytes || Checksum64(bytes.data(), bytes.size()) != file.checksum) {
    return Status::Corruption(path + ": " + std::to_string(bytes.size()) +
                              " bytes that are not the ones the manifest names (" +
                              std::to_string(file.bytes) + " bytes, checksum mismatch)");
  }
  return bytes;
}

Result<MinedVersion> OpenOnce(const std::string& out_dir) {
  MinedVersion version;
  version.out_dir = out_dir;
  MOTIF_ASSIGN_OR_RETURN(version.manifest, ReadManifest(out_dir));
  const ReindexManifest& manifest = version.manifest;
  // The files first, the archive last: a missing file is the sign of a removed version.
  const std::string trellis_path = InOutDir(out_dir, manifest.trellis.path);
  MOTIF_ASSIGN_OR_RETURN(version.trellis, TrellisFileReader::Open(trellis_path));
  if (version.trellis->identity() != manifest.trellis.checksum ||
      version.trellis->file_bytes() != manifest.trellis.bytes) {
    return Status::Corruption(trellis_path + ": not the trellis the manifest names");
  }
  MOTIF_ASSIGN_OR_RETURN(std::string paths_bytes, ReadChecked(out_dir, manifest.paths));
  MOTIF_ASSIGN_OR_RETURN(version.paths, PathsFileReader::FromBytes(
                                            paths_bytes, InOutDir(out_dir, manifest.paths.path)));
  MOTIF_ASSIGN_OR_RETURN(std::string motifs_text, ReadChecked(out_dir, manifest.motifs));
  MOTIF_ASSIGN_OR_RETURN(version.motifs,
                         ParseMotifsJson(motifs_text, InOutDir(out_dir, manifest.motifs.path)));
  ResolveArchivePath(InOutDir(out_dir, manifest.motifs.path), &version.motifs);
  MOTIF_ASSIGN_OR_RETURN(version.archive, FrameFileReader::OpenCommit(
                                              manifest.archive.path, manifest.archive.generation,
                                              manifest.archive.committed_bytes));
  if (version.archive->summary().identity != manifest.archive.identity) {
    return Status::Corruption(manifest.archive.path + ": version " +
                              std::to_string(manifest.archive.generation) +
                              " is not the one the manifest names (another archive?)");
  }
  return version;
}

}  // namespace

Result<MinedVersion> OpenMinedVersion(const std::string& out_dir, int attempts) {
  Result<MinedVersion> opened = OpenOnce(out_dir);
  for (int attempt = 1; attempt < attempts && !opened.ok() && opened.status().IsNotFound() &&
                        fs::exists(ManifestPath(out_dir));
       ++attempt) {
    opened = OpenOnce(out_dir);  // a newer manifest names files that exist
  }
  return opened;
}

Status VerifyMinedVersion(const std::string& out_dir, std::vector<std::string>* notes) {
  MOTIF_ASSIGN_OR_RETURN(MinedVersion version, OpenMinedVersion(out_dir));
  const ReindexManifest& manifest = version.manifest;
  MOTIF_RETURN_IF_ERROR(version.trellis->Verify());
  MOTIF_RETURN_IF_ERROR(version.archive->Verify());
  const TrellisParams& params = version.trellis->params();
  if (params.archive_identity != manifest.archive.identity ||
      params.frame_count != manifest.archive.frames) {
    return Status::Corruption(version.trellis->path() +
                              ": built over another archive version "
                              "than the manifest names");
  }
  if (version.paths->params().trellis_identity != version.trellis->identity()) {
    return Status::Corruption(version.paths->path() + ": grown from another trellis");
  }
  if (version.motifs.frames != manifest.archive.frames ||
      version.motifs.archive_version.identity != manifest.archive.identity) {
    return Status::Corruption(InOutDir(out_dir, manifest.motifs.path) +
                              ": mined from another archive version");
  }
  if (!manifest.report.path.empty()) {
    MOTIF_RETURN_IF_ERROR(ReadChecked(out_dir, manifest.report).status());
  }
  // OUTDIR/motifs.json: this version's, or the previous one's until the next run publishes it.
  const std::string top = InOutDir(out_dir, "motifs.json");
  MOTIF_ASSIGN_OR_RETURN(std::string top_text, ReadFileToString(top));
  if (top_text.size() != manifest.motifs.bytes ||
      Checksum64(top_text.data(), top_text.size()) != manifest.motifs.checksum) {
    MOTIF_RETURN_IF_ERROR(ParseMotifsJson(top_text, top).status());
    if (notes) {
      notes->push_back(top +
                       " is an earlier version's (a run ended between the switch and its "
                       "publication; the next run replaces it)");
    }
  }
  return Status::Ok();
}

}  // namespace motif
