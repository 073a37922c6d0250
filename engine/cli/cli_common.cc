#include "engine/cli/cli_common.h"
#include "engine/report/report_html.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <set>
#include <sstream>

#include "engine/cli/mined_folder.h"
#include "engine/cli/numeric_options.h"
#include "engine/cli/table_options.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif::cli {

namespace po = boost::program_options;

int ExitCodeFor(const Status& status) {
  if (status.ok()) return kExitOk;
  return kExitStatusBase + static_cast<int>(status.code());
}

int ReportError(const std::string& command, const Status& status) {
  std::fprintf(stderr, "motifmine %s: error: %s\n", command.c_str(), FlagMessage(status).c_str());
  return ExitCodeFor(status);
}

void AddProgressOptions(CommandSpec& spec) {
  spec.options.add_options()("quiet,q", "print no progress, only the result and errors")(
      "progress", po::value<std::string>()->default_value("auto"),
      "progress display: auto (in place on a terminal, a line every 5 s otherwise), json "
      "(one JSON object per line on stderr, for logs and other tools), quiet");
}

void AddVerboseOption(CommandSpec& spec) {
  spec.options.add_options()("verbose", "also print details: the search index's parameters");
}

ProgressMode ProgressModeFrom(const po::variables_map& vm) {
  if (vm.count("quiet")) return ProgressMode::kQuiet;
  ProgressMode mode = ProgressMode::kAuto;
  ParseProgressMode(vm["progress"].as<std::string>(), &mode);
  return mode;
}

namespace {

// Every archive this run opens: refused when its newest commit is damaged, unless --allow-older
// is given; then used at its previous version, with one warning per archive on stderr.
void InstallOlderVersionPolicy(const std::string& command, bool allow_older) {
  SetOlderVersionHandler(
      [command, allow_older](const std::string& path, const FrameFileSummary& opened) -> Status {
        const std::string previous = "the previous version (generation " +
                                     std::to_string(opened.generation) + ", " +
                                     std::to_string(opened.file_bytes) + " bytes)";
        if (!allow_older) {
          return Status::Corruption(opened.fallback_reason + "; not reading " + previous +
                                    " in its place: run `motifmine verify " + path +
                                    "`, or give --allow-older to work on it");
        }
        static std::mutex mutex;
        static std::set<std::string> warned;
        std::lock_guard<std::mutex> lock(mutex);
        if (warned.insert(path).second) {
          std::fprintf(stderr, "motifmine %s: warning: %s; working on %s, as --allow-older asks\n",
                       command.c_str(), opened.fallback_reason.c_str(), previous.c_str());
        }
        return Status::Ok();
      });
}

// ARCHIVE given as a folder `mine` wrote: the archive mined there (mined_folder.h).
void UseTheArchiveOfAMinedFolder(const std::string& command, po::variables_map* vm) {
  if (!ReadsArchiveArgument(command) || !vm->count("archive")) return;
  boost::any& value = vm->at("archive").value();
  const std::string* given = boost::any_cast<std::string>(&value);
  if (given == nullptr) return;
  const std::string mined = ArchiveOfMinedFolder(*given);
  if (mined.empty()) return;
  vm->insert({kMinedFolderKey, po::variable_value(boost::any(*given), false)});
  value = mined;
}

}  // namespace

int ParseCommand(CommandSpec& spec, const std::vector<std::string>& args, po::variables_map* vm) {
  spec.options.add_options()("help,h", "show this help")(
      "allow-older",
      "an archive whose newest commit is damaged is read at its previous version, with a "
      "warning (without it the command refuses, exit 12)");
  po::options_description hidden("hidden");
  po::positional_options_description positional;
  for (const auto& [name, count] : spec.positional) {
    if (count == 1) {
      hidden.add_options()(name.c_str(), po::value<std::string>());
    } else {
      hidden.add_options()(name.c_str(), po::value<std::vector<std::string>>()->multitoken());
    }
    positional.add(name.c_str(), count);
  }
  po::options_description all;
  all.add(spec.options).add(hidden);
  // Hidden: the options as JSON, for the test that holds them against the option table and
  // for other tools (shell completion).
  if (std::find(args.begin(), args.end(), "--options-json") != args.end()) {
    std::printf("%s\n", OptionsJson(spec).c_str());
    return kExitOk;
  }
  auto print_help = [&](FILE* out) {
    std::fprintf(out, "usage: %s\n\n%s\n\n", spec.usage.c_str(), spec.summary.c_str());
    std::ostringstream text;
    text << spec.options;
    std::fprintf(out, "%s", text.str().c_str());
  };
  try {
    const po::parsed_options parsed =
        po::command_line_parser(args).options(all).positional(positional).run();
    po::store(parsed, *vm);
    if (vm->count("help")) {
      print_help(stdout);
      return kExitOk;
    }
    po::notify(*vm);
    const Status numbers = CheckNumericOptions(spec.name, parsed, *vm);
    if (!numbers.ok()) throw po::error(numbers.message());
    const Status table = CheckTableFlags(spec, *vm);
    if (!table.ok()) throw po::error(table.message());
    // verify reads the previous version to report on it: the damage is its finding.
    if (spec.name != "verify") InstallOlderVersionPolicy(spec.name, vm->count("allow-older") > 0);
  } catch (const po::error& error) {
    std::fprintf(stderr, "motifmine %s: %s\nusage: %s\n(see motifmine %s --help)\n",
                 spec.name.c_str(), error.what(), spec.usage.c_str(), spec.name.c_str());
    return kExitUsage;
  }
  for (const auto& [name, count] : spec.positional) {
    if (count != -1 && !vm->count(name)) {
      std::fprintf(stderr, "motifmine %s: missing %s\nusage: %s\n(see motifmine %s --help)\n",
                   spec.name.c_str(), name.c_str(), spec.usage.c_str(), spec.name.c_str());
      return kExitUsage;
    }
  }
  UseTheArchiveOfAMinedFolder(spec.name, vm);
  if (vm->count("progress")) {
    ProgressMode mode;
    if (!ParseProgressMode((*vm)["progress"].as<std::string>(), &mode)) {
      std::fprintf(stderr, "motifmine %s: --progress must be auto, json or quiet\n",
                   spec.name.c_str());
      return kExitUsage;
    }
  }
  return -1;
}

po::typed_value<double>* NumberWithDefault(double value) {
  char text[32];
  const auto [end, error] = std::to_chars(text, text + sizeof(text), value);
  return po::value<double>()->default_value(
      value, error == std::errc() ? std::string(text, end) : std::to_string(value));
}

std::string FormatBytes(uint64_t bytes) {
  char text[32];
  if (bytes < 1000000) {
    std::snprintf(text, sizeof(text), "%.1f KB", static_cast<double>(bytes) / 1e3);
  } else {
    std::snprintf(text, sizeof(text), "%.1f MB", static_cast<double>(bytes) / 1e6);
  }
  return text;
}

std::string Percent(uint64_t part, uint64_t whole) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f%%",
                whole ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0);
  return text;
}

Status ParseGroups(const std::string& text, uint32_t* groups) {
  if (text == "auto") {
    *groups = 0;
    return Status::Ok();
  }
  char* end = nullptr;
  const unsigned long value = std::strtoul(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || value == 0 || value > 1000000 || text[0] == '-') {
    return Status::InvalidArgument("--groups must be auto or a positive number, not '" + text +
                                   "'");
  }
  *groups = static_cast<uint32_t>(value);
  return Status::Ok();
}

void AddWordsReaderOptions(CommandSpec& spec, const std::string& files_read,
                           const std::string& name) {
  spec.options.add_options()("prefix", po::value<std::string>()->default_value(""),
                             ("read " + files_read + " (default: ARCHIVE without .mfs)").c_str())(
      "out", po::value<std::string>()->default_value(""),
      ("output folder (default: the archive's): " + name + ".json, " + name + ".html").c_str());
  AddTableFlags(spec, {"threads"});
}

Result<WordsReaderOutput> WordsReaderOutputFrom(const po::variables_map& vm,
                                                const std::string& archive,
                                                const std::string& name) {
  WordsReaderOutput output;
  const std::string prefix = vm["prefix"].as<std::string>();
  output.prefix_archive = prefix.empty() ? archive : prefix + ".mfs";
  std::string out_dir = vm["out"].as<std::string>();
  if (out_dir.empty()) out_dir = std::filesystem::path(archive).parent_path().string();
  if (out_dir.empty()) out_dir = ".";
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) return Status::IOError("cannot create " + out_dir + ": " + error.message());
  output.json_path = (std::filesystem::path(out_dir) / (name + ".json")).string();
  output.html_path = (std::filesystem::path(out_dir) / (name + ".html")).string();
  return output;
}

void ReportSkippedTakes(const std::string& command, const std::vector<std::string>& failures,
                        ProgressMode mode) {
  if (mode != ProgressMode::kQuiet) return;  // the progress display named them already
  for (const std::string& failure : failures) {
    std::fprintf(stderr, "motifmine %s: skipped: %s\n", command.c_str(), failure.c_str());
  }
}

Status ParseFirstFrame(const std::string& text, FirstFramePolicy* policy) {
  if (text == "auto") {
    *policy = FirstFramePolicy::kAuto;
  } else if (text == "keep") {
    *policy = FirstFramePolicy::kKeep;
  } else if (text == "drop") {
    *policy = FirstFramePolicy::kDrop;
  } else {
    return Status::InvalidArgument("--first-frame must be auto, keep or drop");
  }
  return Status::Ok();
}

}  // namespace motif::cli
