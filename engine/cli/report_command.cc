// motifmine report DIR [--archive PATH] [--out FILE]: (re)writes the HTML report of a mining
// result from DIR/motifs.json (engine/report/report_html.h).
#include <cstdio>
#include <filesystem>

#include "engine/cli/cli_common.h"
#include "engine/cli/mined_motifs.h"
#include "engine/cli/table_options.h"
#include "engine/evaluation/planted_motif_score.h"
#include "engine/pipeline/run_record.h"
#include "engine/pipeline/stage_options.h"
#include "engine/report/report_html.h"
#include "engine/synth/truth_json_reader.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

void AddReportOptions(CommandSpec& spec) {
  spec.name = "report";
  spec.usage =
      "motifmine report DIR [--archive PATH] [--out FILE.html] [--view side|front] "
      "[--truth FILE.truth.json]";
  spec.summary =
      "Writes the visual report of DIR/motifs.json (the output of `motifmine cluster`) as one\n"
      "self-contained HTML file (default DIR/report.html): an overview, a timeline of the\n"
      "instances in every clip, and each motif with stick-figure keyframes of its instances.\n"
      "The frames come from the archive named in motifs.json, or --archive if it has moved.";
  ReportOptions defaults;
  spec.options.add_options()("archive", po::value<std::string>()->default_value(""),
                             "the archive (default: the one named in motifs.json)")(
      "out", po::value<std::string>()->default_value(""),
      "the HTML file (default: DIR/report.html)")(
      "view", po::value<std::string>()->default_value("side"),
      "side (the skeleton's Z axis to the right) or front (its X axis)")(
      "keyframes", po::value<uint32_t>()->default_value(defaults.keyframes),
      "stick figures per instance")(
      "instances", po::value<uint32_t>()->default_value(defaults.instances_per_motif),
      "instances drawn per motif")(
      "eager", po::value<uint32_t>()->default_value(defaults.eager_motifs),
      "motifs whose figures are written as SVG; the rest are drawn by the page's script")(
      "truth", po::value<std::string>()->default_value(""),
      "a synthetic archive's truth file: add recall, precision and ARI to the overview");
  AddTableFlags(spec, {"playback-mb"});
  spec.positional = {{"dir", 1}};
}

// The command line of `report`, read back and checked.
struct ReportCommandOptions {
  std::string dir;
  std::string archive;     // "": the one motifs.json names
  std::string out;         // "": DIR/report.html
  std::string truth_path;  // "": the mine run's, if any
  ReportOptions report;
};

// Fills *command; returns -1 to go on, or the exit code after printing the error.
int ReadReportOptions(const CommandSpec& spec, const po::variables_map& vm,
                      ReportCommandOptions* command) {
  ReportOptions& options = command->report;
  const std::string view = vm["view"].as<std::string>();
  if (view != "side" && view != "front") {
    return ReportError("report",
                       Status::InvalidArgument("--view must be side or front, not '" + view + "'"));
  }
  options.view = view == "side" ? FigureView::kSide : FigureView::kFront;
  options.keyframes = vm["keyframes"].as<uint32_t>();
  options.instances_per_motif = vm["instances"].as<uint32_t>();
  options.eager_motifs = vm["eager"].as<uint32_t>();
  motifmine::MineOptions mine;
  ReadTableFlags(spec, vm, &mine);
  options.playback_bytes = ReportOptionsFor(mine).playback_bytes;
  command->dir = vm["dir"].as<std::string>();
  command->archive = vm["archive"].as<std::string>();
  command->out = vm["out"].as<std::string>();
  command->truth_path = vm["truth"].as<std::string>();
  return -1;
}

// The overview of the `mine` run that wrote this motifs.json, when its record still matches
// (a record that cannot be used is noted on stderr), and the score against the truth file.
Result<ReportInfo> ReportInfoFor(const MinedMotifs& mined, const std::string& truth_path) {
  ReportInfo info;
  info.archive_path = mined.archive->path();
  info.truth_path = truth_path;
  const std::string run_path =
      (std::filesystem::path(mined.motifs_path).parent_path() / "run.json").string();
  if (Result<RunRecord> run = ReadRunRecord(run_path, mined.motifs_path); run.ok()) {
    info.parameters_text = run->parameters_text;
    // The stages mine's own report showed: its report stage came after that page was made.
    for (const RunStageTiming& timing : run->timings) {
      if (timing.stage != "report") info.timings.push_back({timing.stage, timing.seconds});
    }
    info.peak_memory_bytes = run->peak_memory_bytes;
    info.descriptions = run->descriptions;
    if (info.truth_path.empty()) info.truth_path = run->truth_path;
  } else if (!run.status().IsNotFound()) {
    std::fprintf(stderr, "motifmine report: note: %s not used: %s\n", run_path.c_str(),
                 run.status().message().c_str());
  }
  if (!info.truth_path.empty()) {
    MOTIF_ASSIGN_OR_RETURN(TruthFile truth, ReadTruthJson(info.truth_path));
    info.planted_score = ScoreMotifsDocument(mined.document, truth.instances);
  }
  return info;
}

}  // namespace

int RunReport(const std::vector<std::string>& args) {
  CommandSpec spec;
  AddReportOptions(spec);
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  ReportCommandOptions command;
  if (int code = ReadReportOptions(spec, vm, &command); code >= 0) return code;

  Result<MinedMotifs> mined = OpenMinedMotifs(command.dir, command.archive);
  if (!mined.ok()) return ReportError("report", mined.status());
  Result<ReportInfo> info = ReportInfoFor(*mined, command.truth_path);
  if (!info.ok()) return ReportError("report", info.status());
  std::string out = command.out;
  if (out.empty()) {
    out = (std::filesystem::path(mined->motifs_path).parent_path() / "report.html").string();
  }
  if (Status status = WriteReportHtml(out, mined->document, *mined->archive, *info, command.report);
      !status.ok()) {
    return ReportError("report", status);
  }
  std::error_code error;
  const uintmax_t bytes = std::filesystem::file_size(out, error);
  std::printf("wrote %s (%s motifs, %.1f KiB)\n", out.c_str(),
              WithCommas(mined->document.motifs.size()).c_str(),
              error ? 0.0 : static_cast<double>(bytes) / 1024.0);
  return kExitOk;
}

}  // namespace motif::cli
