#include "engine/cli/table_options.h"

#include <algorithm>
#include <optional>

#include <nlohmann/json.hpp>

#include "engine/cli/numeric_options.h"
#include "engine/pipeline/option_table.h"

namespace motif::cli {

namespace po = boost::program_options;

const std::vector<std::string> kRadiusFlags = {"eps", "eps-rule", "eps-angle"};
const std::vector<std::string> kTrellisFlags = {"kmax", "exclusion", "search", "weights"};
const std::vector<std::string> kLshFlags = {"tables",
                                            "hashes",
                                            "width",
                                            "width-per-hash",
                                            "probes",
                                            "max-candidates",
                                            "ranking",
                                            "max-entries",
                                            "chain",
                                            "chained-max-candidates",
                                            "chain-probe-every",
                                            "chain-sweeps"};
const std::vector<std::string> kGrowFlags = {"branch", "min-length", "all-branches"};
const std::vector<std::string> kClusterFlags = {"groups",          "similarity",  "max-ncut",
                                                "min-similarity",  "pause-speed", "pause-seconds",
                                                "max-length-ratio"};
const std::vector<std::string> kRunFlags = {"seed", "threads"};

std::vector<std::string> AllTableFlags() {
  std::vector<std::string> names;
  for (const OptionSpec& spec : MineOptionSpecs()) names.push_back(spec.info.name);
  return names;
}

namespace {

const OptionSpec& SpecNamed(const std::string& name) {
  const OptionSpec* spec = FindMineOption(name);
  if (spec == nullptr || spec->info.name != name) {
    std::fprintf(stderr, "motifmine: '%s' is not in the option table\n", name.c_str());
    std::abort();  // a command declares a flag the table does not have: our bug
  }
  return *spec;
}

void ReadNamedFlags(const po::variables_map& vm, const std::vector<std::string>& names,
                    motifmine::MineOptions* options, std::set<std::string>* given) {
  for (const std::string& name : names) {
    if (!vm.count(name)) continue;
    const bool is_switch = SpecNamed(name).type == OptionType::kSwitch;
    const std::string text = is_switch ? "true" : vm[name].as<std::string>();
    // CheckTableFlags accepted every value already, and a default is the table's own.
    (void)SetOptionFromText(options, name, text);
    if (given != nullptr && !vm[name].defaulted()) given->insert(name);
  }
}

std::string RecordedHelp(const OptionSpec& spec) {
  return spec.info.help + " (default: the recorded value; at the first run " +
         (spec.type == OptionType::kSwitch ? std::string("not given") : spec.info.default_value) +
         ")";
}

}  // namespace

void AddTableFlags(CommandSpec& spec, const std::vector<std::string>& names,
                   TableDefaults defaults) {
  for (const std::string& name : names) {
    const OptionSpec& option = SpecNamed(name);
    spec.table_flags.push_back(name);
    const std::string help =
        defaults == TableDefaults::kRecorded ? RecordedHelp(option) : option.info.help;
    if (option.type == OptionType::kSwitch) {
      spec.options.add_options()(name.c_str(), help.c_str());
    } else if (defaults == TableDefaults::kRecorded) {
      spec.options.add_options()(name.c_str(), po::value<std::string>(), help.c_str());
    } else {
      spec.options.add_options()(name.c_str(),
                                 po::value<std::string>()->default_value(option.info.default_value),
                                 help.c_str());
    }
  }
}

void ReadTableFlags(const CommandSpec& spec, const po::variables_map& vm,
                    motifmine::MineOptions* options, std::set<std::string>* given) {
  ReadNamedFlags(vm, spec.table_flags, options, given);
}

void ReadTableFlags(const po::variables_map& vm, const std::vector<std::string>& names,
                    motifmine::MineOptions* options) {
  ReadNamedFlags(vm, names, options, nullptr);
}

Status CheckTableFlags(const CommandSpec& spec, const po::variables_map& vm) {
  for (const std::string& name : spec.table_flags) {
    if (!vm.count(name) || vm[name].defaulted()) continue;
    if (SpecNamed(name).type == OptionType::kSwitch) continue;
    motifmine::MineOptions scratch;
    Status status = SetOptionFromText(&scratch, name, vm[name].as<std::string>());
    if (!status.ok()) return Status::InvalidArgument(FlagMessage(status));
  }
  return Status::Ok();
}

namespace {

const char* ValueTypeName(const po::value_semantic* semantic) {
  if (semantic->max_tokens() == 0) return "switch";
  if (dynamic_cast<const po::typed_value<std::string>*>(semantic)) return "string";
  if (dynamic_cast<const po::typed_value<uint32_t>*>(semantic)) return "uint32";
  if (dynamic_cast<const po::typed_value<uint64_t>*>(semantic)) return "uint64";
  if (dynamic_cast<const po::typed_value<int>*>(semantic)) return "int";
  if (dynamic_cast<const po::typed_value<double>*>(semantic)) return "double";
  if (dynamic_cast<const po::typed_value<float>*>(semantic)) return "float";
  if (dynamic_cast<const po::typed_value<bool>*>(semantic)) return "bool";
  return "other";
}

// "arg (=256)" -> "256"; no "(=": none.
std::optional<std::string> ShownDefault(const po::option_description& option) {
  const std::string text = option.format_parameter();
  const size_t at = text.find("(=");
  if (at == std::string::npos || text.back() != ')') return std::nullopt;
  return text.substr(at + 2, text.size() - at - 3);
}

// A table option's range: "kind" (its OptionType's name), "min", "max", "min_exclusive"; nothing
// for one that is not a number (a choice, text, a switch).
void AddTableRange(const OptionSpec& spec, nlohmann::json* option) {
  switch (spec.type) {
    case OptionType::kChoice:
    case OptionType::kText:
    case OptionType::kSwitch:
      return;
    default:
      break;
  }
  (*option)["kind"] = OptionTypeName(spec.type);
  (*option)["min"] = spec.info.min;
  (*option)["max"] = spec.info.max;
  (*option)["min_exclusive"] = spec.info.min_exclusive;
}

// A command's own numeric flag's range (numeric_options.h): "kind" count, number or groups
// ("auto" or a count), "min",
// "max", "min_exclusive", "zero_allowed".
void AddFlagRange(const FlagRange& range, const std::string& type, nlohmann::json* option) {
  const bool whole = type == "uint32" || type == "uint64" || type == "int";
  (*option)["kind"] = range.auto_allowed ? "groups" : whole ? "count" : "number";
  (*option)["min"] = range.min;
  (*option)["max"] = range.max;
  (*option)["min_exclusive"] = range.min_exclusive;
  (*option)["zero_allowed"] = range.zero_allowed;
}

}  // namespace

std::string OptionsJson(const CommandSpec& spec) {
  nlohmann::json options = nlohmann::json::array();
  for (const auto& option : spec.options.options()) {
    const std::string name = option->long_name();
    const std::optional<std::string> shown = ShownDefault(*option);
    const bool table =
        std::find(spec.table_flags.begin(), spec.table_flags.end(), name) != spec.table_flags.end();
    const std::string type = ValueTypeName(option->semantic().get());
    nlohmann::json entry = {{"name", name},
                            {"type", type},
                            {"default", shown ? nlohmann::json(*shown) : nlohmann::json(nullptr)},
                            {"table", table}};
    if (table) {
      AddTableRange(SpecNamed(name), &entry);
    } else if (const FlagRange* range = FindFlagRange(spec.name, name)) {
      AddFlagRange(*range, type, &entry);
    }
    options.push_back(std::move(entry));
  }
  return options.dump();
}

std::string FlagMessage(const Status& status) {
  const std::string& message = status.message();
  const std::string& option = status.option();
  if (option.empty()) return message;
  // The first occurrence of the name as a word: after the start, a space or '(', before the
  // end, a space, ')', ',' or ':'.
  const auto word_at = [&](size_t at) {
    const bool starts = at == 0 || message[at - 1] == ' ' || message[at - 1] == '(';
    const size_t end = at + option.size();
    const bool ends = end == message.size() || message[end] == ' ' || message[end] == ')' ||
                      message[end] == ',' || message[end] == ':';
    return starts && ends;
  };
  size_t at = message.find(option);
  while (at != std::string::npos && !word_at(at)) at = message.find(option, at + 1);
  if (at == std::string::npos) return message;
  std::string flag = option;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return message.substr(0, at) + "--" + flag + message.substr(at + option.size());
}

}  // namespace motif::cli
