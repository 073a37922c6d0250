// The option table: every option of a mining run (motifmine::MineOptions,
// include/motifmine/options.h) with its name, type, range and help, and how it reads and writes
// its field. It is the one definition the tool's flags (engine/cli/table_options.h), the Python
// keywords, the public SetMineOption and the reindex manifest's parameters are made from; the
// defaults themselves are include/motifmine/defaults.h's, read back from a default MineOptions.
// A name is the flag without "--" ("kmax", "min-length"); the Python keyword is the same with '_'
// for '-'. Errors name the option (Status::InvalidOption), never a flag.
// Thread-safety: the table is built once (a function-local static) and read-only after.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "common/status.h"
#include "motifmine/options.h"

namespace motif {

enum class OptionType {
  kCount,    // a whole number >= 0, within [min, max]
  kInteger,  // a whole number, within [min, max]
  kNumber,   // a finite number, within [min, max] (the least value refused if min_exclusive)
  kChoice,   // one of `choices`
  kText,     // any text (a path)
  kSwitch,   // given or not ("true" / "false" as text)
  kLength,   // frames ("60") or seconds ("0.5s"), > 0
  kGroups,   // "auto" or a count >= 1
  kRadius,   // "auto" (0) or a number >= 0
};

// "count", "integer", ...: OptionInfo::type.
const char* OptionTypeName(OptionType type);

struct OptionSpec {
  motifmine::OptionInfo info;  // name, type, default, range, choices, field, aliases, help
  OptionType type = OptionType::kText;
  std::function<std::string(const motifmine::MineOptions&)> get;
  // Parses `text` and stores it; InvalidOption naming info.name when it is not a valid value.
  std::function<Status(motifmine::MineOptions*, const std::string& text)> set;
};

// Every option, in the order `motifmine mine --help` lists them.
const std::vector<OptionSpec>& MineOptionSpecs();

// The option named `name`, or one of its aliases (with '_' or '-'); null if there is none.
// An alias that is not the option itself under another name (min_length_seconds: a number of
// seconds; write_report: the inverse of no-report) is resolved by SetMineOption.
const OptionSpec* FindMineOption(const std::string& name);

// Sets an option by name or alias from text; InvalidOption for an unknown name or a bad value.
Status SetOptionFromText(motifmine::MineOptions* options, const std::string& name,
                         const std::string& text);
// The option's value as text (by name or alias); empty for an unknown name.
std::string OptionAsText(const motifmine::MineOptions& options, const std::string& name);

// Every option's value is one its own `set` accepts (in range, a known choice), and the rules
// between options hold; the first violation as InvalidOption.
Status CheckMineOptions(const motifmine::MineOptions& options);

// The shortest text that reads back as `value` ("0.2", "12", "1e-05").
std::string FormatOptionNumber(double value);

}  // namespace motif
