#include "engine/cli/mined_folder.h"

#include <algorithm>
#include <array>
#include <filesystem>

#include "engine/cluster/motifs_json.h"
#include "engine/trellis/trellis_builder.h"

namespace motif {
namespace {

namespace fs = std::filesystem;

bool Exists(const fs::path& path) {
  std::error_code error;
  return fs::exists(path, error);
}

}  // namespace

std::string ArchiveOfMinedFolder(const std::string& path) {
  std::error_code error;
  const fs::path folder(path);
  if (!fs::is_directory(folder, error)) return "";
  if (Exists(folder / "motifs.json")) {
    Result<MotifsDocument> motifs = ReadMotifsJson((folder / "motifs.json").string());
    // The reader resolves a relative archive against the folder.
    if (motifs.ok() && !motifs->archive.empty()) return motifs->archive;
  }
  if (Exists(folder / "archive.mfs")) return (folder / "archive.mfs").string();
  return "";
}

bool ReadsArchiveArgument(const std::string& command) {
  static constexpr std::array<const char*, 7> kReaders = {"graph",    "words", "search", "segment",
                                                          "classify", "info",  "export"};
  return std::find(kReaders.begin(), kReaders.end(), command) != kReaders.end();
}

std::string MinedTrellisOf(const std::string& folder, const FrameFileReader& archive) {
  const fs::path dir = folder.empty() ? fs::path(".") : fs::path(folder);
  const fs::path trellis = dir / "trellis.mtr";
  if (!Exists(dir / "mine_state.json")) return "";
  return IsTrellisOfArchive(trellis.string(), archive) ? trellis.string() : "";
}

}  // namespace motif
