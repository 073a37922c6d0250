#include "engine/cli/cli_common.h"

#include <cstdio>
#include <iostream>
#include <sstream>

namespace motif::cli {

namespace po = boost::program_options;

int ExitCodeFor(const Status& status) {
  if (status.ok()) return kExitOk;
  return kExitStatusBase + static_cast<int>(status.code());
}

int ReportError(const std::string& command, const Status& status) {
  std::fprintf(stderr, "motifmine %s: error: %s\n", command.c_str(), status.message().c_str());
  return ExitCodeFor(status);
}

void AddProgressOptions(CommandSpec& spec) {
  spec.options.add_options()
      ("quiet,q", "print no progress, only the result and errors")
      ("progress", po::value<std::string>()->default_value("auto"),
       "progress display: auto (in place on a terminal, a line every 5 s otherwise), json "
       "(one JSON object per line on stderr, for logs and other tools), quiet");
}

ProgressMode ProgressModeFrom(const po::variables_map& vm) {
  if (vm.count("quiet")) return ProgressMode::kQuiet;
  ProgressMode mode = ProgressMode::kAuto;
  ParseProgressMode(vm["progress"].as<std::string>(), &mode);
  return mode;
}

int ParseCommand(CommandSpec& spec, const std::vector<std::string>& args, po::variables_map* vm) {
  spec.options.add_options()("help,h", "show this help");
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
  auto print_help = [&](FILE* out) {
    std::fprintf(out, "usage: %s\n\n%s\n\n", spec.usage.c_str(), spec.summary.c_str());
    std::ostringstream text;
    text << spec.options;
    std::fprintf(out, "%s", text.str().c_str());
  };
  try {
    po::store(po::command_line_parser(args).options(all).positional(positional).run(), *vm);
    if (vm->count("help")) {
      print_help(stdout);
      return kExitOk;
    }
    po::notify(*vm);
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

std::string WithCommas(uint64_t value) {
  std::string digits = std::to_string(value);
  std::string out;
  for (size_t idx = 0; idx < digits.size(); ++idx) {
    if (idx > 0 && (digits.size() - idx) % 3 == 0) out += ',';
    out += digits[idx];
  }
  return out;
}

}  // namespace motif::cli
