#include "engine/pipeline/option_table.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace motif {
namespace {

using motifmine::MineOptions;

// The largest thread count accepted: more than any machine this runs on has cores, and TBB
// fails beyond what the process may create.
constexpr double kMaxThreads = 4096;
// The largest synthetic archive: 10^8 frames, about 7 GB, the largest size the project measures.
constexpr double kMaxSynthFrames = 1e8;

std::string Lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string RangeText(const motifmine::OptionInfo& info) {
  return std::string(info.min_exclusive ? "(" : "[") + FormatOptionNumber(info.min) + ", " +
         FormatOptionNumber(info.max) + "]";
}

Status OutOfRange(const motifmine::OptionInfo& info, const std::string& text,
                  const std::string& what) {
  return Status::InvalidOption(
      info.name, "must be " + what + " in " + RangeText(info) + ", not '" + text + "'");
}

// A whole number within the option's range; negative numbers only for kInteger options.
Result<long double> ParseWholeNumber(const motifmine::OptionInfo& info, const std::string& text,
                                     bool allow_negative) {
  const char* what = "a whole number";
  if (text.empty() || (!allow_negative && text.find('-') != std::string::npos)) {
    return OutOfRange(info, text, what);
  }
  errno = 0;
  char* end = nullptr;
  long double value = 0;
  if (allow_negative) {
    value = static_cast<long double>(std::strtoll(text.c_str(), &end, 10));
  } else {
    value = static_cast<long double>(std::strtoull(text.c_str(), &end, 10));
  }
  if (end == text.c_str() || *end != '\0' || errno == ERANGE || value < info.min ||
      value > info.max) {
    return OutOfRange(info, text, what);
  }
  return value;
}

// A finite number within the option's range.
Result<double> ParseNumber(const motifmine::OptionInfo& info, const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  const bool below = info.min_exclusive ? value <= info.min : value < info.min;
  if (text.empty() || end == text.c_str() || *end != '\0' || !std::isfinite(value) || below ||
      value > info.max) {
    return OutOfRange(info, text, "a number");
  }
  return value;
}

Result<bool> ParseSwitch(const motifmine::OptionInfo& info, const std::string& text) {
  const std::string lower = Lower(text);
  if (lower == "true" || lower == "1" || lower == "yes") return true;
  if (lower == "false" || lower == "0" || lower == "no") return false;
  return Status::InvalidOption(info.name, "must be true or false, not '" + text + "'");
}

motifmine::OptionInfo Info(const char* name, OptionType type, const char* field, const char* help) {
  motifmine::OptionInfo info;
  info.name = name;
  info.type = OptionTypeName(type);
  info.field = field;
  info.help = help;
  return info;
}

template <typename T>
OptionSpec WholeOption(const char* name, T MineOptions::*field, const char* field_name, double min,
                       double max, const char* help) {
  constexpr bool kSigned = std::numeric_limits<T>::is_signed;
  OptionSpec spec;
  spec.type = kSigned ? OptionType::kInteger : OptionType::kCount;
  spec.info = Info(name, spec.type, field_name, help);
  spec.info.min = min;
  spec.info.max = max;
  spec.get = [field](const MineOptions& options) { return std::to_string(options.*field); };
  spec.set = [field, info = spec.info](MineOptions* options, const std::string& text) -> Status {
    MOTIF_ASSIGN_OR_RETURN(const long double value, ParseWholeNumber(info, text, kSigned));
    options->*field = static_cast<T>(value);
    return Status::Ok();
  };
  return spec;
}

OptionSpec NumberOption(const char* name, double MineOptions::*field, const char* field_name,
                        double min, double max, bool min_exclusive, const char* help) {
  OptionSpec spec;
  spec.type = OptionType::kNumber;
  spec.info = Info(name, spec.type, field_name, help);
  spec.info.min = min;
  spec.info.max = max;
  spec.info.min_exclusive = min_exclusive;
  spec.get = [field](const MineOptions& options) { return FormatOptionNumber(options.*field); };
  spec.set = [field, info = spec.info](MineOptions* options, const std::string& text) -> Status {
    MOTIF_ASSIGN_OR_RETURN(options->*field, ParseNumber(info, text));
    return Status::Ok();
  };
  return spec;
}

OptionSpec ChoiceOption(const char* name, std::string MineOptions::*field, const char* field_name,
                        std::vector<std::string> choices, const char* help) {
  OptionSpec spec;
  spec.type = OptionType::kChoice;
  spec.info = Info(name, spec.type, field_name, help);
  spec.info.choices = std::move(choices);
  spec.get = [field](const MineOptions& options) { return options.*field; };
  spec.set = [field, info = spec.info](MineOptions* options, const std::string& text) -> Status {
    if (std::find(info.choices.begin(), info.choices.end(), text) == info.choices.end()) {
      std::string list;
      for (size_t index = 0; index < info.choices.size(); ++index) {
        list += (index == 0                         ? ""
                 : index + 1 == info.choices.size() ? " or "
                                                    : ", ") +
                info.choices[index];
      }
      return Status::InvalidOption(info.name, "must be " + list + ", not '" + text + "'");
    }
    options->*field = text;
    return Status::Ok();
  };
  return spec;
}

OptionSpec TextOption(const char* name, std::string MineOptions::*field, const char* field_name,
                      const char* help) {
  OptionSpec spec;
  spec.type = OptionType::kText;
  spec.info = Info(name, spec.type, field_name, help);
  spec.get = [field](const MineOptions& options) { return options.*field; };
  spec.set = [field](MineOptions* options, const std::string& text) -> Status {
    options->*field = text;
    return Status::Ok();
  };
  return spec;
}

// A switch; `inverted`: the field is true when the switch is not given (--no-report).
OptionSpec SwitchOption(const char* name, bool MineOptions::*field, const char* field_name,
                        bool inverted, const char* help) {
  OptionSpec spec;
  spec.type = OptionType::kSwitch;
  spec.info = Info(name, spec.type, field_name, help);
  spec.get = [field, inverted](const MineOptions& options) {
    return (options.*field != inverted) ? "true" : "false";
  };
  spec.set = [field, inverted, info = spec.info](MineOptions* options,
                                                 const std::string& text) -> Status {
    MOTIF_ASSIGN_OR_RETURN(const bool on, ParseSwitch(info, text));
    options->*field = on != inverted;
    return Status::Ok();
  };
  return spec;
}

// --min-length: frames ("60") or seconds ("0.5s").
OptionSpec MinLengthOption() {
  OptionSpec spec;
  spec.type = OptionType::kLength;
  spec.info = Info("min-length", spec.type, "min_length_frames, min_length_seconds",
                   "least motif length lambda, on both sides of a match: frames (60) or seconds "
                   "(0.5s)");
  spec.info.min = 0;
  spec.info.max = 86400;
  spec.info.min_exclusive = true;
  spec.get = [](const MineOptions& options) {
    return options.min_length_frames > 0 ? std::to_string(options.min_length_frames)
                                         : FormatOptionNumber(options.min_length_seconds) + "s";
  };
  spec.set = [info = spec.info](MineOptions* options, const std::string& text) -> Status {
    const auto bad = [&] {
      return Status::InvalidOption(
          info.name,
          "must be a number of frames (60) or of seconds (0.5s) above 0, not '" + text + "'");
    };
    if (!text.empty() && text.back() == 's') {
      Result<double> seconds = ParseNumber(info, text.substr(0, text.size() - 1));
      if (!seconds.ok()) return bad();
      options->min_length_seconds = *seconds;
      options->min_length_frames = 0;
      return Status::Ok();
    }
    motifmine::OptionInfo frames = info;
    frames.min = 1;
    frames.max = 1e9;
    frames.min_exclusive = false;
    Result<long double> count = ParseWholeNumber(frames, text, false);
    if (!count.ok()) return bad();
    options->min_length_frames = static_cast<uint64_t>(*count);
    return Status::Ok();
  };
  return spec;
}

// --groups: "auto" (0) or a count.
OptionSpec GroupsOption() {
  OptionSpec spec;
  spec.type = OptionType::kGroups;
  spec.info = Info("groups", spec.type, "groups",
                   "number of motifs G, or auto (cut while a cut's Ncut is below --max-ncut)");
  spec.info.min = 1;
  spec.info.max = 1e6;
  spec.get = [](const MineOptions& options) {
    return options.groups == 0 ? std::string("auto") : std::to_string(options.groups);
  };
  spec.set = [info = spec.info](MineOptions* options, const std::string& text) -> Status {
    if (text == "auto") {
      options->groups = 0;
      return Status::Ok();
    }
    Result<long double> count = ParseWholeNumber(info, text, false);
    if (!count.ok()) {
      return Status::InvalidOption(info.name,
                                   "must be auto or a number of motifs >= 1, not '" + text + "'");
    }
    options->groups = static_cast<uint32_t>(*count);
    return Status::Ok();
  };
  return spec;
}

// --eps: "auto" (0: by --eps-rule) or a radius.
OptionSpec RadiusOption() {
  OptionSpec spec;
  spec.type = OptionType::kRadius;
  spec.info = Info("eps", spec.type, "eps",
                   "neighbour radius in units of the pose distance, or auto (chosen by "
                   "--eps-rule)");
  spec.info.min = 0;
  spec.info.max = 1e6;
  spec.get = [](const MineOptions& options) {
    return options.eps == 0 ? std::string("auto") : FormatOptionNumber(options.eps);
  };
  spec.set = [info = spec.info](MineOptions* options, const std::string& text) -> Status {
    if (text == "auto") {
      options->eps = 0;
      return Status::Ok();
    }
    Result<double> eps = ParseNumber(info, text);
    if (!eps.ok()) {
      return Status::InvalidOption(info.name, "must be auto or a number in " + RangeText(info) +
                                                  " (0: auto), not '" + text + "'");
    }
    options->eps = *eps;
    return Status::Ok();
  };
  return spec;
}

void AddTrellisOptions(std::vector<OptionSpec>* table) {
  table->push_back(RadiusOption());
  table->push_back(ChoiceOption("eps-rule", &MineOptions::eps_rule, "eps_rule",
                                {"joint-angle", "paper"},
                                "how eps is chosen when --eps is not given: joint-angle (poses "
                                "match when their weighted joints differ by about --eps-angle "
                                "degrees) or paper (mu - 2 sigma of sampled pair distances, Meng "
                                "et al. 2008)"));
  table->push_back(NumberOption("eps-angle", &MineOptions::eps_angle_degrees, "eps_angle_degrees",
                                0, 180, true,
                                "the joint-angle rule's tolerated rotation per weighted joint, "
                                "in degrees"));
  table->back().info.aliases = {"eps_angle_degrees"};
  table->push_back(WholeOption("kmax", &MineOptions::k_max, "k_max", 1, 65535,
                               "neighbours kept per frame, the nearest"));
  table->back().info.aliases = {"k_max"};
  table->push_back(WholeOption("exclusion", &MineOptions::exclusion_frames, "exclusion_frames", 0,
                               1e9,
                               "frames of the same clip closer than this are never neighbours "
                               "(0: half the minimum length)"));
  table->push_back(ChoiceOption("search", &MineOptions::search, "search", {"auto", "lsh", "exact"},
                                "how columns are found: lsh, exact (blocked brute force, O(N^2)), "
                                "or auto (exact on small archives, lsh on large ones)"));
  table->push_back(TextOption("weights", &MineOptions::weights_path, "weights_path",
                              "per-joint weights file (\"joint weight\" lines) overriding the "
                              "defaults"));
}

void AddLshOptions(std::vector<OptionSpec>* table) {
  table->push_back(
      WholeOption("tables", &MineOptions::lsh_tables, "lsh_tables", 1, 64, "LSH hash tables"));
  table->push_back(WholeOption("hashes", &MineOptions::lsh_hashes, "lsh_hashes", 0, 64,
                               "LSH projections per table (0: from the archive's size)"));
  table->push_back(NumberOption("width", &MineOptions::lsh_width, "lsh_width", 0, 1e6, false,
                                "LSH bucket width (0: from the data)"));
  table->push_back(NumberOption(
      "width-per-hash", &MineOptions::lsh_width_per_hash, "lsh_width_per_hash", 0, 100, true,
      "LSH cell width per projection, relative to the measured neighbour distance (the width is "
      "this x projections per table x the 90th percentile of a column's neighbours' embedding "
      "distance)"));
  table->push_back(WholeOption("probes", &MineOptions::lsh_probes, "lsh_probes", 1, 4096,
                               "LSH buckets visited per table (multi-probe)"));
  table->push_back(WholeOption("max-candidates", &MineOptions::lsh_max_candidates,
                               "lsh_max_candidates", 1, 1 << 24,
                               "LSH: at most this many exact distance evaluations a column"));
  table->push_back(ChoiceOption("ranking", &MineOptions::lsh_ranking, "lsh_ranking",
                                {"sort", "code"},
                                "LSH candidate order: sort (fastest) or code (ranks gathered "
                                "entries by position code: better recall on low-contrast "
                                "archives, ~1.5-2.5x the time)"));
  table->push_back(WholeOption("max-entries", &MineOptions::lsh_max_entries, "lsh_max_entries", 1,
                               1 << 26,
                               "LSH, --ranking code: bucket entries gathered and ranked per "
                               "column"));
  table->push_back(WholeOption("chain", &MineOptions::lsh_chain_columns, "lsh_chain_columns", 0,
                               1 << 20,
                               "LSH: columns searched as chains of this many, each seeded with "
                               "its predecessor's neighbours (0: every column alone)"));
  table->push_back(WholeOption("chained-max-candidates", &MineOptions::lsh_chained_max_candidates,
                               "lsh_chained_max_candidates", 0, 1 << 24,
                               "LSH: evaluations a probing chained column spends on the probed "
                               "buckets after its seeds"));
  table->push_back(WholeOption(
      "chain-probe-every", &MineOptions::lsh_chain_probe_every, "lsh_chain_probe_every", 1, 1 << 16,
      "LSH: only every this-many-th column of a chain probes the buckets (with "
      "--chained-max-candidates); the columns between keep their seeds and what the chain "
      "sweeps carry over (1: every column probes)"));
  table->push_back(WholeOption("chain-sweeps", &MineOptions::lsh_chain_sweeps, "lsh_chain_sweeps",
                               0, 64,
                               "LSH: passes over each finished chain, backward then forward, in "
                               "which every column verifies its neighbour column's neighbours "
                               "moved by up to 2 frames (0: none)"));
}

void AddGrowAndClusterOptions(std::vector<OptionSpec>* table) {
  table->push_back(WholeOption("branch", &MineOptions::branch, "branch", 1, 1000,
                               "branching factor B of the path grower"));
  table->push_back(MinLengthOption());
  table->push_back(SwitchOption("all-branches", &MineOptions::all_branches, "all_branches", false,
                                "keep every path of a tree that died long enough (default: the "
                                "longest of each tree)"));
  table->push_back(GroupsOption());
  table->push_back(ChoiceOption(
      "similarity", &MineOptions::similarity, "similarity", {"warped", "shared"},
      "how instance pairs are weighted for the normalized cut: warped (the time-warped distance "
      "of their motions, each instance scaled by its nearest repetition) or shared (the similar "
      "frames they share, as in the paper)"));
  table->push_back(NumberOption("max-ncut", &MineOptions::max_ncut, "max_ncut", 0, 2, true,
                                "automatic groups: stop cutting a group when its best cut's "
                                "Ncut (0..2) is not below this"));
  table->push_back(NumberOption("min-similarity", &MineOptions::min_similarity, "min_similarity", 0,
                                1, true,
                                "instance pairs sharing less than this fraction of the shorter "
                                "get no edge"));
  table->push_back(NumberOption("max-length-ratio", &MineOptions::max_length_ratio,
                                "max_length_ratio", 0, 1e6, false,
                                "drop an instance from its motif when its length is more than "
                                "this factor from the motif's median (0 keeps all; else >= 1)"));
  table->push_back(NumberOption(
      "pause-speed", &MineOptions::pause_speed, "pause_speed", 0, 1e6, false,
      "instances are trimmed to their movement: a pause, at least --pause-seconds in which the "
      "joints turn slower than this (degrees per second, on average), is never an instance's "
      "head or tail (0: no trimming)"));
  table->push_back(NumberOption("pause-seconds", &MineOptions::pause_seconds, "pause_seconds", 0,
                                3600, true, "the shortest pause, seconds"));
}

void AddRunOptions(std::vector<OptionSpec>* table) {
  table->push_back(WholeOption("seed", &MineOptions::seed, "seed", 0, 18446744073709551615.0,
                               "seed of every random choice"));
  table->push_back(WholeOption("threads", &MineOptions::threads, "threads", 0, kMaxThreads,
                               "threads (0: all cores)"));
  table->push_back(SwitchOption("skip-bad", &MineOptions::skip_bad, "skip_bad", false,
                                "import: report malformed takes and import the others"));
  table->push_back(TextOption("descriptions", &MineOptions::descriptions_path, "descriptions_path",
                              "import: a tab-separated index with 'file' and 'description' "
                              "columns; the report shows each take's description"));
  table->push_back(SwitchOption("no-report", &MineOptions::write_report, "write_report", true,
                                "do not write report.html"));
  table->push_back(WholeOption("playback-mb", &MineOptions::playback_mb, "playback_mb", 0, 4096,
                               "MB of playback data in report.html (the player of every "
                               "instance), motifs in rank order; 0: none"));
  table->push_back(WholeOption("synth-frames", &MineOptions::synth_frames, "synth_frames", 1,
                               kMaxSynthFrames, "no INPUT: frames of the synthetic archive"));
  table->push_back(WholeOption("synth-motifs", &MineOptions::synth_motifs, "synth_motifs", 0, 10000,
                               "no INPUT: planted motifs of the synthetic archive"));
}

std::vector<OptionSpec> MakeTable() {
  std::vector<OptionSpec> table;
  AddTrellisOptions(&table);
  AddLshOptions(&table);
  AddGrowAndClusterOptions(&table);
  AddRunOptions(&table);
  const MineOptions defaults;
  for (OptionSpec& spec : table) spec.info.default_value = spec.get(defaults);
  return table;
}

// "k_max" and "k-max" are the same name.
std::string Dashed(std::string name) {
  std::replace(name.begin(), name.end(), '_', '-');
  return name;
}

// The older Python keywords that are not an option under another name, as text for the option.
bool TranslateAlias(const std::string& name, const std::string& text, std::string* option,
                    std::string* value) {
  const std::string dashed = Dashed(name);
  if (dashed == "min-length-seconds") {
    *option = "min-length";
    *value = text + "s";
  } else if (dashed == "min-length-frames") {
    *option = "min-length";
    *value = text;
  } else if (dashed == "write-report") {
    *option = "no-report";
    Result<bool> on = ParseSwitch(Info("write_report", OptionType::kSwitch, "", ""), text);
    *value = on.ok() ? (*on ? "false" : "true") : text;
  } else {
    return false;
  }
  return true;
}

}  // namespace

const char* OptionTypeName(OptionType type) {
  switch (type) {
    case OptionType::kCount:
      return "count";
    case OptionType::kInteger:
      return "integer";
    case OptionType::kNumber:
      return "number";
    case OptionType::kChoice:
      return "choice";
    case OptionType::kText:
      return "text";
    case OptionType::kSwitch:
      return "switch";
    case OptionType::kLength:
      return "length";
    case OptionType::kGroups:
      return "groups";
    case OptionType::kRadius:
      return "radius";
  }
  return "?";
}

std::string FormatOptionNumber(double value) {
  if (value == std::floor(value) && std::fabs(value) < 1e16) {
    return std::to_string(static_cast<int64_t>(value));  // 1000000000, not 1e+09
  }
  char text[64];
  const std::to_chars_result result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

const std::vector<OptionSpec>& MineOptionSpecs() {
  static const std::vector<OptionSpec> table = MakeTable();
  return table;
}

const OptionSpec* FindMineOption(const std::string& name) {
  const std::string dashed = Dashed(name);
  for (const OptionSpec& spec : MineOptionSpecs()) {
    if (spec.info.name == dashed) return &spec;
    for (const std::string& alias : spec.info.aliases) {
      if (Dashed(alias) == dashed) return &spec;
    }
  }
  return nullptr;
}

Status SetOptionFromText(motifmine::MineOptions* options, const std::string& name,
                         const std::string& text) {
  std::string option = name;
  std::string value = text;
  if (!FindMineOption(name)) TranslateAlias(name, text, &option, &value);
  const OptionSpec* spec = FindMineOption(option);
  if (spec == nullptr) return Status::InvalidOption(name, "is not an option of a mining run");
  Status status = spec->set(options, value);
  if (!status.ok() && option != name) {  // an alias: name what was given
    return Status::InvalidOption(
        name, "must be a valid value, not '" + text + "' (" + status.message() + ")");
  }
  return status;
}

std::string OptionAsText(const motifmine::MineOptions& options, const std::string& name) {
  const OptionSpec* spec = FindMineOption(name);
  return spec ? spec->get(options) : std::string();
}

Status CheckMineOptions(const motifmine::MineOptions& options) {
  for (const OptionSpec& spec : MineOptionSpecs()) {
    motifmine::MineOptions copy;
    MOTIF_RETURN_IF_ERROR(spec.set(&copy, spec.get(options)));
  }
  return Status::Ok();
}

}  // namespace motif
