// motifmine verify PATH: every checksum, every block decoded, of an archive (.mfs), a trellis
// (.mtr), a paths file (.mpa), or the current version of a reindex output folder (its
// manifest.json and everything it names).
#include <cstdio>
#include <filesystem>

#include "engine/cli/cli_common.h"
#include "engine/reindex/mined_version.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/paths_file/paths_file_reader.h"
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

int VerifyOutput(const std::string& dir) {
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

}  // namespace

int RunVerify(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "verify";
  spec.usage = "motifmine verify PATH";
  spec.summary =
      "Checks PATH: an archive (.mfs: its header, footer and metadata checksums, then every\n"
      "block's checksum and that it decodes), a trellis (.mtr) or paths file (.mpa) likewise,\n"
      "or a `motifmine reindex` output folder (its manifest and every file of the current\n"
      "version, with the archive version they were mined from). Exits 0 when all is well, 12\n"
      "(corruption) naming the first damage, 11 when a file is missing.";
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const std::string path = vm["archive"].as<std::string>();
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) return VerifyOutput(path);
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension == ".mtr") return VerifyTrellis(path);
  if (extension == ".mpa") return VerifyPaths(path);
  return VerifyArchive(path, ProgressModeFrom(vm));
}

}  // namespace motif::cli
