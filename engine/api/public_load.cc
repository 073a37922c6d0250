// motifmine::LoadMineResult (include/motifmine/mine.h): a mining result read back from its
// output folder (OUT/motifs.json through the engine's reader, which skips fields it does not
// know; OUT/run.json through its reader, which checks it still describes that motifs.json).
#include <filesystem>
#include <string>

#include "engine/api/public_motifs.h"
#include "engine/api/public_status.h"
#include "engine/pipeline/run_record.h"
#include "motifmine/mine.h"

namespace motifmine {
namespace {

namespace fs = std::filesystem;

// run.json's parameters read "radius: <how eps was chosen>; neighbour search: <mode>"
// (MinePipeline::ParametersText): the part MineParameters::eps_how holds.
std::string EpsHow(const std::string& parameters_text) {
  const std::string radius = "radius: ";
  const std::string search = "; neighbour search: ";
  if (parameters_text.rfind(radius, 0) != 0) return parameters_text;
  const size_t end = parameters_text.rfind(search);
  return parameters_text.substr(radius.size(),
                                end == std::string::npos ? std::string::npos : end - radius.size());
}

// The archive motifs.json names, or the folder's own when that one is gone (a moved folder
// whose motifs.json, of version 1, named it from where the run was).
std::string ArchivePath(const std::string& out_dir, const std::string& named) {
  std::error_code error;
  const std::string inside = (fs::path(out_dir) / "archive.mfs").string();
  if (!fs::exists(named, error) && fs::is_regular_file(inside, error)) return inside;
  return named;
}

}  // namespace

Status LoadMineResult(const std::string& out_dir, MineResult* result) {
  if (result == nullptr) return {Status::Code::kInvalidArgument, "no MineResult to fill"};
  std::error_code error;
  if (!fs::is_directory(out_dir, error)) {
    return {Status::Code::kNotFound,
            out_dir + ": no such folder (`motifmine mine --out " + out_dir + "` writes one)"};
  }
  const std::string motifs_path = (fs::path(out_dir) / "motifs.json").string();
  if (!fs::exists(motifs_path, error)) {
    return {Status::Code::kNotFound, motifs_path + " does not exist: " + out_dir +
                                         " is not a folder `motifmine mine` wrote"};
  }
  motif::Result<motif::MotifsDocument> document = motif::ReadMotifsJson(motifs_path);
  if (!document.ok()) return motif::ToPublicStatus(document.status());
  *result = MineResult();
  motif::CopyMotifsDocument(*document, result);
  const motif::MotifsJsonParams& params = document->params;
  result->parameters = {params.eps, "", params.kmax, params.branch, params.min_length, params.seed};
  result->archive_path = ArchivePath(out_dir, document->archive);
  result->motifs_path = motifs_path;
  // run.json is optional (a `cluster` run writes none), and stale once motifs.json changed.
  motif::Result<motif::RunRecord> run =
      motif::ReadRunRecord((fs::path(out_dir) / "run.json").string(), motifs_path);
  if (run.ok()) {
    result->parameters.eps_how = EpsHow(run->parameters_text);
    for (const motif::RunStageTiming& time : run->timings) {
      result->timings.push_back({time.stage, time.seconds, time.reused});
    }
  }
  return {};
}

}  // namespace motifmine
