// motifmine grow ARCHIVE [...]: grows the paths of ARCHIVE's matching trellis (the streaming
// path grower) into the paths file, or reuses an up-to-date one.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "engine/cli/cli_common.h"
#include "engine/cli/table_options.h"
#include "engine/grow/paths_builder.h"
#include "engine/trellis/trellis_builder.h"

namespace motif::cli {

namespace po = boost::program_options;

int RunGrow(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "grow";
  spec.usage =
      "motifmine grow ARCHIVE [--trellis PATH] [--branch B] [--min-length L] "
      "[--all-branches] [--out PATH]";
  spec.summary =
      "Grows continuous paths through ARCHIVE's matching trellis (built by `motifmine trellis`)\n"
      "with the streaming tree-growing scheme of Meng et al. 2008, and writes the candidates\n"
      "(paths at least --min-length long on both sides; the longest of each tree unless\n"
      "--all-branches) to ARCHIVE.mpa. A path at frame j may\n"
      "continue to frames j .. j+B-1 of the next column; paths never cross a clip boundary.\n"
      "An existing paths file grown from the same trellis with the same parameters is reused.";
  spec.options.add_options()("trellis", po::value<std::string>()->default_value(""),
                             "default: ARCHIVE.mtr")(
      "out", po::value<std::string>()->default_value(""), "paths file (default ARCHIVE.mpa)");
  AddTableFlags(spec, kGrowFlags);
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const std::string archive = vm["archive"].as<std::string>();
  std::string trellis = vm["trellis"].as<std::string>();
  if (trellis.empty()) trellis = DefaultTrellisPath(archive);
  std::string out = vm["out"].as<std::string>();
  if (out.empty()) out = DefaultPathsPath(archive);

  motifmine::MineOptions mine;
  ReadTableFlags(spec, vm, &mine);
  PathsOptions options;
  options.branch = mine.branch;
  options.all_branches = mine.all_branches;
  options.min_length_frames = mine.min_length_frames;
  options.min_length_seconds = mine.min_length_seconds;
  ProgressReporter progress(ProgressModeFrom(vm));
  bool started = false;
  options.progress = [&](uint64_t done, uint64_t total) {
    if (!started) progress.BeginStage("grow", total, "columns");
    started = true;
    progress.Update(done);
  };
  Result<PathsReport> report = BuildPaths(archive, trellis, out, options);
  if (started) progress.EndStage();
  if (!report.ok()) return ReportError("grow", report.status());

  const PathsParams& params = report->params;
  if (report->reused) {
    std::printf("%s is up to date (same trellis and parameters): reused\n", out.c_str());
  } else {
    std::printf("wrote %s\n", out.c_str());
  }
  std::printf("  candidates   %s paths of at least %llu frames on both sides (%s)\n",
              WithCommas(report->candidates).c_str(),
              static_cast<unsigned long long>(params.min_length),
              params.all_branches ? "every branch" : "the longest of each tree");
  std::printf("  trellis      %s (%s columns, %s entries)\n", trellis.c_str(),
              WithCommas(params.frame_count).c_str(), WithCommas(report->trellis_entries).c_str());
  std::printf("  branch       %u\n", params.branch);
  if (!report->reused) {
    const GrowStats& stats = report->stats;
    std::printf("  trees        %s roots, %s paths died, %s of them long enough\n",
                WithCommas(stats.trees).c_str(), WithCommas(stats.dead_paths).c_str(),
                WithCommas(stats.long_paths).c_str());
    std::printf("  time         grow %.2fs (%.1f M entries/s), write %.2fs\n", report->grow_seconds,
                report->grow_seconds > 0
                    ? static_cast<double>(stats.entries) / report->grow_seconds / 1e6
                    : 0.0,
                report->write_seconds);
    std::printf("  memory       grower %s, peak resident %s\n",
                FormatBytes(stats.memory_bytes).c_str(), FormatBytes(PeakResidentBytes()).c_str());
  }
  return kExitOk;
}

}  // namespace motif::cli
