// Checks of the numbers given on a command line, for every command at once: boost's parser
// turns "--kmax=-1" into 4294967295 and reads "nan" and "inf" as numbers, so a negative count, a
// number that is not finite or one beyond what the command can do would otherwise run (or
// allocate without bound). Every number a command declares itself (not one of the option table's:
// those have their ranges there, table_options.h) has its range in one table, FlagRanges(), with
// why. Called by ParseCommand; a failed check is a usage error (exit code 2).
#pragma once

#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "common/status.h"

namespace motif::cli {

// The values a command's numeric flag accepts: [min, max] ((min, max] if min_exclusive), and 0
// too when zero_allowed (0 means "not given": a frame rate taken from the take). A flag declared
// as text with auto_allowed is "auto" or a whole number in the range (classify --groups).
struct FlagRange {
  const char* command;  // "import"
  const char* flag;     // "block-frames"
  double min = 0;
  double max = 0;
  bool min_exclusive = false;
  bool zero_allowed = false;
  bool auto_allowed = false;
};

// Every numeric flag's range, by command (engine/cli/numeric_options.cc says why each bound).
const std::vector<FlagRange>& FlagRanges();

// The range of `command`'s flag `flag`; null if it has none (a text flag, or the option table's).
const FlagRange* FindFlagRange(const std::string& command, const std::string& flag);

// Every option of `parsed` that the user gave: an unsigned option must not be negative, a
// floating-point one must be finite, and each within its range (FindFlagRange). The message names
// the flag, the range and the value. (A numeric flag without a range would only be checked for
// its sign and finiteness: scripts/option_sweep.py fails on one.)
Status CheckNumericOptions(const std::string& command,
                           const boost::program_options::parsed_options& parsed,
                           const boost::program_options::variables_map& vm);

}  // namespace motif::cli
