// motifmine import ARCHIVE PATH...: creates or appends to an archive.
#include <cstdio>

#include "engine/cli/cli_common.h"
#include "engine/cli/table_options.h"
#include "engine/ingest/archive_import.h"
#include "formats/import/take_descriptions.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

void AddImportOptions(CommandSpec& spec) {
  spec.name = "import";
  spec.usage = "motifmine import ARCHIVE PATH... [options]";
  spec.summary =
      "Imports BVH files and ASF/AMC takes (files, or folders searched recursively) into ARCHIVE\n"
      "(.mfs), creating it or appending to it. Existing clips are never rewritten; if anything\n"
      "fails, the archive is left exactly as it was. A take already in the archive (same file\n"
      "content) is skipped. An AMC file is paired with the ASF in its folder (or the one sharing\n"
      "its subject prefix); --asf names it outright.";
  spec.options.add_options()(
      "fps", NumberWithDefault(0),
      "frame rate of a NEW archive (takes at other rates are resampled); default: the first "
      "take's rate")("asf", po::value<std::string>()->default_value(""),
                     "the ASF skeleton for every AMC file")(
      "amc-fps", NumberWithDefault(120.0),
      "frame rate of AMC files (they store none)")(
      "bvh-fps", NumberWithDefault(0),
      "override every BVH file's Frame Time with this rate")(
      "first-frame", po::value<std::string>()->default_value("auto"),
      "auto: drop a first frame that is a converter's T-pose (discontinuous with the take); "
      "keep; drop")("block-frames", po::value<uint32_t>()->default_value(4096),
                    "frames per column block");
  AddTableFlags(spec, {"skip-bad", "descriptions", "threads"});
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}, {"paths", -1}};
}

// The command line of `import`, read back and checked (the progress callbacks are not set).
struct ImportCommandOptions {
  std::string archive;
  std::vector<std::string> paths;
  ArchiveImportOptions import;
  ProgressMode progress_mode = ProgressMode::kAuto;
};

// Fills *command; returns -1 to go on, or the exit code after printing the usage error (no
// PATH) or the error (a bad value, a descriptions index that cannot be read).
int ReadImportOptions(const CommandSpec& spec, const po::variables_map& vm,
                      ImportCommandOptions* command) {
  if (!vm.count("paths")) {
    std::fprintf(stderr, "motifmine import: give at least one PATH to import\nusage: %s\n",
                 spec.usage.c_str());
    return kExitUsage;
  }
  ArchiveImportOptions& options = command->import;
  options.fps = vm["fps"].as<double>();
  options.import.asf_path = vm["asf"].as<std::string>();
  options.import.amc_fps = vm["amc-fps"].as<double>();
  options.import.bvh_fps = vm["bvh-fps"].as<double>();
  if (Status status =
          ParseFirstFrame(vm["first-frame"].as<std::string>(), &options.import.first_frame);
      !status.ok()) {
    return ReportError("import", status);
  }
  motifmine::MineOptions table;
  ReadTableFlags(spec, vm, &table);
  options.skip_bad = table.skip_bad;
  if (const std::string index = table.descriptions_path; !index.empty()) {
    Result<std::unordered_map<std::string, std::string>> descriptions = ReadTakeDescriptions(index);
    if (!descriptions.ok()) return ReportError("import", descriptions.status());
    options.import.descriptions = std::move(*descriptions);
  }
  options.block_frames = vm["block-frames"].as<uint32_t>();  // in range: CheckNumericOptions
  options.threads = table.threads;
  command->archive = vm["archive"].as<std::string>();
  command->paths = vm["paths"].as<std::vector<std::string>>();
  command->progress_mode = ProgressModeFrom(vm);
  return -1;
}

// The import, its notes and its one "import" stage (counted in takes, opened by the first
// report) shown by `progress`.
Result<ArchiveImportResult> ImportWithProgress(const ImportCommandOptions& command,
                                               ProgressReporter& progress) {
  ArchiveImportOptions options = command.import;
  options.note = [&](const std::string& message) { progress.Note(message); };
  bool stage_started = false;
  options.progress = [&](uint64_t done, uint64_t total) {
    if (!stage_started) {
      progress.BeginStage("import", total, "takes");
      stage_started = true;
    }
    progress.Update(done);
  };
  Result<ArchiveImportResult> result = ImportIntoArchive(command.archive, command.paths, options);
  if (stage_started) progress.EndStage();
  return result;
}

void PrintImportSummary(const std::string& archive, const ArchiveImportResult& result) {
  std::printf("%s %s: %s imported (%s)", result.created ? "created" : "appended to",
              archive.c_str(), CountOf(result.takes_imported, "take").c_str(),
              CountOf(result.frames_added, "frame").c_str());
  if (result.takes_mapped) {
    std::printf(", %s mapped onto the CMU body", WithCommas(result.takes_mapped).c_str());
  }
  if (result.takes_already_present) {
    std::printf(", %s already present", WithCommas(result.takes_already_present).c_str());
  }
  if (result.takes_failed) {
    std::printf(", %s failed", WithCommas(result.takes_failed).c_str());
  }
  std::printf("; the archive now holds %s, %s at %g fps\n",
              CountOf(result.archive_clips, "clip").c_str(),
              CountOf(result.archive_frames, "frame").c_str(), result.fps);
}

}  // namespace

int RunImport(const std::vector<std::string>& args) {
  CommandSpec spec;
  AddImportOptions(spec);
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  ImportCommandOptions command;
  if (int code = ReadImportOptions(spec, vm, &command); code >= 0) return code;

  ProgressReporter progress(command.progress_mode);
  Result<ArchiveImportResult> result = ImportWithProgress(command, progress);
  if (!result.ok()) {
    int code = ReportError("import", result.status());
    std::fprintf(stderr, "motifmine import: nothing was imported; %s is unchanged\n",
                 command.archive.c_str());
    return code;
  }
  PrintImportSummary(command.archive, *result);
  if (result->takes_failed == 0) return kExitOk;
  ReportSkippedTakes("import", result->failures, command.progress_mode);
  return kExitWarnings;  // the good takes are stored; the bad ones are named
}

}  // namespace motif::cli
