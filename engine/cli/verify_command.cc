// motifmine verify PATH: every checksum, every block decoded, of an archive (.mfs), a trellis
// (.mtr), a paths file (.mpa), the current version of a reindex output folder (its
// manifest.json and everything it names), or a mine output folder (its files).
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "engine/cli/cli_common.h"
#include "engine/cluster/motifs_json.h"
#include "engine/reindex/mined_version.h"
#include "formats/frame_file/frame_file_format.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/paths_file/paths_file_format.h"
#include "formats/paths_file/paths_file_reader.h"
#include "formats/trellis_file/trellis_file_format.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

int VerifyArchive(const std::string& path, ProgressMode mode) {
  Result<std::unique_ptr<FrameFileReader>> opened = FrameFileReader::Open(path);
  if (!opened.ok()) return ReportError("verify", opened.status());
  const FrameFileReader& reader = **opened;
  ProgressReporter progress(mode);
  progress.BeginStage("verify", reader.summary().block_count, "blocks");
  Status status = reader.Verify([&](uint64_t done, uint64_t) { progress.Update(done); });
  progress.EndStage();
  if (!status.ok()) return ReportError("verify", status);
  // The version named is the one verified, even when an import appended since it was opened.
  std::printf("OK: %s: generation %llu: %s, %s, %s verified\n", path.c_str(),
              static_cast<unsigned long long>(reader.summary().generation),
              CountOf(reader.summary().block_count, "block").c_str(),
              CountOf(reader.clips().size(), "clip").c_str(),
              CountOf(reader.frame_count(), "frame").c_str());
  return kExitOk;
}

int VerifyTrellis(const std::string& path) {
  Result<std::unique_ptr<TrellisFileReader>> opened = TrellisFileReader::Open(path);
  if (!opened.ok()) return ReportError("verify", opened.status());
  if (Status status = (*opened)->Verify(); !status.ok()) return ReportError("verify", status);
  std::printf("OK: %s: %s columns, %s neighbours in %s blocks verified\n", path.c_str(),
              WithCommas((*opened)->column_count()).c_str(),
              WithCommas((*opened)->neighbour_count()).c_str(),
              WithCommas((*opened)->block_count()).c_str());
  return kExitOk;
}

int VerifyPaths(const std::string& path) {
  Result<std::unique_ptr<PathsFileReader>> opened = PathsFileReader::Open(path);
  if (!opened.ok()) return ReportError("verify", opened.status());
  std::printf("OK: %s: %s candidates verified\n", path.c_str(),
              WithCommas((*opened)->candidates().size()).c_str());
  return kExitOk;
}

// A `mine` output folder (no manifest.json): motifs.json read, the archive it names (or
// DIR/archive.mfs), DIR/trellis.mtr and DIR/paths.mpa verified, those that exist.
int VerifyMineOutput(const std::string& dir) {
  const std::filesystem::path folder(dir);
  std::error_code error;
  std::string archive = (folder / "archive.mfs").string();
  std::string motifs_text;
  if (std::filesystem::exists(folder / "motifs.json", error)) {
    Result<MotifsDocument> motifs = ReadMotifsJson((folder / "motifs.json").string());
    if (!motifs.ok()) return ReportError("verify", motifs.status());
    if (!motifs->archive.empty()) archive = motifs->archive;
    motifs_text = ", motifs.json (" + CountOf(motifs->motifs.size(), "motif") + ")";
  } else if (!std::filesystem::exists(archive, error)) {
    return ReportError("verify", Status::NotFound(dir + ": neither a reindex output folder (no "
                                                  "manifest.json) nor a mine output folder (no "
                                                  "motifs.json or archive.mfs)"));
  }
  if (int code = VerifyArchive(archive, ProgressMode::kQuiet); code != kExitOk) return code;
  std::string verified = archive;
  for (const char* name : {"trellis.mtr", "paths.mpa"}) {
    const std::string path = (folder / name).string();
    if (!std::filesystem::exists(path, error)) continue;
    const int code = std::string(name) == "trellis.mtr" ? VerifyTrellis(path) : VerifyPaths(path);
    if (code != kExitOk) return code;
    verified += std::string(", ") + name;
  }
  std::printf("OK: %s: a mine output folder: %s%s verified\n", dir.c_str(), verified.c_str(),
              motifs_text.c_str());
  return kExitOk;
}

int VerifyOutput(const std::string& dir) {
  std::error_code error;
  if (!std::filesystem::exists(std::filesystem::path(dir) / "manifest.json", error)) {
    return VerifyMineOutput(dir);
  }
  std::vector<std::string> notes;
  if (Status status = VerifyMinedVersion(dir, &notes); !status.ok()) {
    return ReportError("verify", status);
  }
  Result<ReindexManifest> manifest = ReadManifest(dir);
  if (!manifest.ok()) return ReportError("verify", manifest.status());
  for (const std::string& note : notes) std::printf("note: %s\n", note.c_str());
  std::printf(
      "OK: %s: version %llu (%s): archive %s generation %llu (%s frames), trellis, "
      "paths, motifs verified\n",
      dir.c_str(), static_cast<unsigned long long>(manifest->version), manifest->dir.c_str(),
      manifest->archive.path.c_str(), static_cast<unsigned long long>(manifest->archive.generation),
      WithCommas(manifest->archive.frames).c_str());
  return kExitOk;
}

// The file's kind from its first bytes, whatever its name: "mfs", "mtr", "mpa" or "".
std::string KindOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, sizeof magic);
  if (!in) return "";
  if (std::memcmp(magic, frame_file::kFileMagic.data(), 8) == 0) return "mfs";
  if (std::memcmp(magic, trellis_file::kFileMagic.data(), 8) == 0) return "mtr";
  if (std::memcmp(magic, paths_file::kFileMagic.data(), 8) == 0) return "mpa";
  return "";
}

}  // namespace

int RunVerify(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "verify";
  spec.usage = "motifmine verify PATH";
  spec.summary =
      "Checks PATH: an archive (.mfs: its header, footer and metadata checksums, then every\n"
      "block's checksum and that it decodes), a trellis (.mtr) or paths file (.mpa) likewise,\n"
      "a `motifmine reindex` output folder (its manifest and every file of the current\n"
      "version, with the archive version they were mined from), or a `motifmine mine` output\n"
      "folder (its archive, trellis, paths and motifs.json). Exits 0 when all is well, 12\n"
      "(corruption) naming the first damage, 11 when a file is missing, 2 for a file of\n"
      "another kind.";
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const std::string path = vm["archive"].as<std::string>();
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) return VerifyOutput(path);
  std::string kind = std::filesystem::path(path).extension().string();
  kind = kind.empty() ? "" : kind.substr(1);
  // A damaged file keeps its name's kind (exit 12); another regular file is not one verify
  // checks. Only a regular file is peeked at (opening a FIFO would block): the archive reader
  // refuses the rest, naming them.
  const bool regular = std::filesystem::is_regular_file(path, error);
  if (kind != "mfs" && kind != "mtr" && kind != "mpa") kind = regular ? KindOf(path) : "";
  if (kind.empty() && regular) {
    std::fprintf(stderr,
                 "motifmine verify: %s is not an archive (.mfs), trellis (.mtr), paths file "
                 "(.mpa) or output folder: nothing to verify\n",
                 path.c_str());
    return kExitUsage;
  }
  if (kind == "mtr") return VerifyTrellis(path);
  if (kind == "mpa") return VerifyPaths(path);
  return VerifyArchive(path, ProgressModeFrom(vm));
}

}  // namespace motif::cli
