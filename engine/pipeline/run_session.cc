#include "engine/pipeline/run_session.h"

#include <filesystem>
#include <utility>

namespace motif {

RunFiles MineFolderFiles(const std::string& dir) {
  const auto in = [&](const char* name) { return (std::filesystem::path(dir) / name).string(); };
  RunFiles files;
  files.dir = dir;
  files.archive = in("archive.mfs");
  files.trellis = in("trellis.mtr");
  files.paths = in("paths.mpa");
  files.motifs = in("motifs.json");
  files.instances = in("instances.csv");
  files.cluster_state = in("mine_state.json");
  files.report = in("report.html");
  files.run_record = in("run.json");
  return files;
}

RunSession::RunSession(motifmine::MineOptions options, std::vector<std::string> inputs,
                       RunFiles files, RunHooks hooks)
    : options_(std::move(options)),
      inputs_(std::move(inputs)),
      files_(std::move(files)),
      hooks_(std::move(hooks)) {}

void RunSession::Progress(const std::string& stage, uint64_t done, uint64_t total,
                          const std::string& unit) const {
  if (hooks_.progress) hooks_.progress(stage, done, total, unit);
}

void RunSession::Note(const std::string& message) const {
  if (hooks_.note) hooks_.note(message);
}

Status RunSession::OpenArchive(const FrameFileVersion& version) {
  MOTIF_ASSIGN_OR_RETURN(owned_archive_, FrameFileReader::OpenVersion(files_.archive, version));
  archive_ = owned_archive_.get();
  return Status::Ok();
}

void RunSession::SetArchive(std::unique_ptr<FrameFileReader> archive) {
  owned_archive_ = std::move(archive);
  archive_ = owned_archive_.get();
}

Status RunSession::OpenTrellis() {
  MOTIF_ASSIGN_OR_RETURN(trellis_, TrellisFileReader::Open(files_.trellis));
  return Status::Ok();
}

}  // namespace motif
