// The option table's flags on a command line (engine/pipeline/option_table.h): every command
// that takes a mining option declares it with AddTableFlags, so its name, its help, its default
// and the values it accepts are the table's, and reads it back with ReadTableFlags. ParseCommand
// checks each given value against the table before the command runs: a bad value is a usage
// error (exit 2) naming the flag.
#pragma once

#include <set>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "common/status.h"
#include "engine/cli/cli_common.h"
#include "motifmine/options.h"

namespace motif::cli {

// The table's flags each command takes, so that commands taking the same stage take them alike.
extern const std::vector<std::string> kRadiusFlags;   // eps, eps-rule, eps-angle
extern const std::vector<std::string> kTrellisFlags;  // kmax, exclusion, search, weights
extern const std::vector<std::string> kLshFlags;      // tables, hashes, width, ...
extern const std::vector<std::string> kGrowFlags;     // branch, min-length, all-branches
extern const std::vector<std::string> kClusterFlags;  // groups, similarity, max-ncut, ...
extern const std::vector<std::string> kRunFlags;      // seed, threads
// Every flag of the table, in its order (`mine` takes them all).
std::vector<std::string> AllTableFlags();

enum class TableDefaults {
  kShown,     // the default is the table's, shown in the help
  kRecorded,  // no default: unset keeps the recorded value (reindex); the help says the first
              // run's default
};

// Declares the flags `names` (table names) on `spec`, and records them for ParseCommand's check.
void AddTableFlags(CommandSpec& spec, const std::vector<std::string>& names,
                   TableDefaults defaults = TableDefaults::kShown);

// Every table flag of `spec` that has a value (given, or its shown default) into *options; the
// names given on the command line into *given (if not null).
void ReadTableFlags(const CommandSpec& spec, const boost::program_options::variables_map& vm,
                    motifmine::MineOptions* options, std::set<std::string>* given = nullptr);

// The same for the table flags `names` only (a command's own reading step, without its spec).
void ReadTableFlags(const boost::program_options::variables_map& vm,
                    const std::vector<std::string>& names, motifmine::MineOptions* options);

// Called by ParseCommand: each table flag given on the command line is one the table accepts;
// otherwise the message naming the flag ("--kmax must be ...").
Status CheckTableFlags(const CommandSpec& spec, const boost::program_options::variables_map& vm);

// `spec`'s options as a JSON array, one object each: "name", "type" (the value's C++ type:
// "string", "uint32", "uint64", "int", "double", "float", "bool"; "switch" without a value),
// "default" (the text the help shows; null without one), "table" (declared by AddTableFlags) and,
// for a number, its range: "kind" ("count", "number", or the table's "length", "groups",
// "radius"), "min", "max", "min_exclusive" (and "zero_allowed" for a command's own flag), from the
// option table or FlagRanges() (numeric_options.h). Read by scripts/option_sweep.py.
std::string OptionsJson(const CommandSpec& spec);

// A status's message as the tool prints it: an option named by the table ("kmax must be ...")
// as its flag ("--kmax must be ...").
std::string FlagMessage(const Status& status);

}  // namespace motif::cli
