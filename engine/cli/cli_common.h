// What every command of the `motifmine` tool shares: exit codes, error reporting, and parsing of
// its options with Boost.Program_options.
//
// Exit codes (pinned; documented in docs/guide.md for cron users):
//   0 success; 1 internal error; 2 usage error (unknown option, missing argument); 3 done, with
//   warnings (reindex: files not imported);
//   10 + Status code for failures: 11 not found, 12 corruption, 13 invalid input,
//   14 I/O error, 15 not supported, 16 resource exhausted (disk full).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

#include "common/count_text.h"   // WithCommas, CountOf, for the commands' summaries
#include "common/peak_memory.h"  // PeakResidentBytes, for the commands' summaries
#include "common/rank_group.h"
#include "common/status.h"
#include "engine/cli/progress_reporter.h"
#include "engine/cluster/pauses.h"
#include "engine/trellis/trellis_builder.h"
#include "formats/import/take_importer.h"

namespace motif::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitInternal = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitWarnings = 3;
// Names every take --skip-bad passed over on stderr, even under --quiet (the progress display
// names them as they happen otherwise): a skipped take is a warning, never silent.
void ReportSkippedTakes(const std::string& command, const std::vector<std::string>& failures,
                        ProgressMode mode);
inline constexpr int kExitStatusBase = 10;

// 10 + the status code for a failure, 0 for OK.
int ExitCodeFor(const Status& status);

// Prints "motifmine <command>: error: <message>" to stderr and returns ExitCodeFor(status).
int ReportError(const std::string& command, const Status& status);

// A parsed command line. `options` are the named options, `positional` names the positional
// arguments in order (the last one may take any number of values).
struct CommandSpec {
  std::string name;     // "import"
  std::string usage;    // "motifmine import ARCHIVE PATH... [options]"
  std::string summary;  // one paragraph
  boost::program_options::options_description options{"Options", 100};
  std::vector<std::pair<std::string, int>> positional;  // name, count (-1: the rest)
  std::vector<std::string> table_flags;  // the option table's flags it takes (table_options.h)
};

// Parses args (without the command name). On --help prints the help and sets *exit_now = true
// with exit code 0; on a usage error prints it and the usage and returns kExitUsage.
// Returns -1 to go on.
int ParseCommand(CommandSpec& spec, const std::vector<std::string>& args,
                 boost::program_options::variables_map* vm);

// A number option whose help shows its default as a person writes it ("0.2", not
// "0.20000000000000001": the shortest text that reads back as the same double).
boost::program_options::typed_value<double>* NumberWithDefault(double value);

// Adds --quiet and --progress=auto|json|quiet, and reads them back.
void AddProgressOptions(CommandSpec& spec);
// --verbose: details on stderr that a user rarely needs (the search index's parameters).
void AddVerboseOption(CommandSpec& spec);
ProgressMode ProgressModeFrom(const boost::program_options::variables_map& vm);

// "24.0 KB", "1.6 MB".
std::string FormatBytes(uint64_t bytes);
// part / whole as "57.2%" (0.0% when whole is 0).
std::string Percent(uint64_t part, uint64_t whole);

// --groups: "auto" (*groups = 0) or a positive number. InvalidArgument otherwise.
Status ParseGroups(const std::string& text, uint32_t* groups);
// --first-frame: "auto", "keep" or "drop". InvalidArgument otherwise.
Status ParseFirstFrame(const std::string& text, FirstFramePolicy* policy);

// What `search` and `classify` share: --prefix (where `motifmine words` wrote its files), --out
// (the folder for DIR/<name>.json and DIR/<name>.html, default the archive's) and --threads.
void AddWordsReaderOptions(CommandSpec& spec, const std::string& files_read,
                           const std::string& name);
struct WordsReaderOutput {
  std::string prefix_archive;  // the archive path whose words files to read (PREFIX.mfs or ARCHIVE)
  std::string json_path;       // DIR/<name>.json
  std::string html_path;       // DIR/<name>.html
};
// Reads those options back and creates DIR. IOError if DIR cannot be created.
Result<WordsReaderOutput> WordsReaderOutputFrom(const boost::program_options::variables_map& vm,
                                                const std::string& archive,
                                                const std::string& name);

int RunImport(const std::vector<std::string>& args);
int RunInfo(const std::vector<std::string>& args);
int RunVerify(const std::vector<std::string>& args);
int RunExport(const std::vector<std::string>& args);
int RunSynth(const std::vector<std::string>& args);
int RunTrellis(const std::vector<std::string>& args);
int RunInspectTrellis(const std::vector<std::string>& args);
int RunGrow(const std::vector<std::string>& args);
int RunCluster(const std::vector<std::string>& args);
int RunExportMotif(const std::vector<std::string>& args);
int RunReport(const std::vector<std::string>& args);
int RunMine(const std::vector<std::string>& args);
// `mine` on the ranks of a distributed run (motifmine-mpi; every rank calls it with the same
// args): rank 0 prints as `mine` does, the others only an error of their own, after which
// `abort_all(exit code)` ends every rank. `default_threads` replaces --threads 0 (all cores).
struct MineAcrossRanks {
  RankGroup* ranks = nullptr;
  int default_threads = 0;
  std::function<void(int exit_code)> abort_all;
};
int RunMineAcrossRanks(const std::vector<std::string>& args, const MineAcrossRanks& across);
int RunWords(const std::vector<std::string>& args);
int RunClassify(const std::vector<std::string>& args);
int RunSegment(const std::vector<std::string>& args);
int RunGraph(const std::vector<std::string>& args);
int RunSearch(const std::vector<std::string>& args);
int RunReindex(const std::vector<std::string>& args);
int RunScore(const std::vector<std::string>& args);

}  // namespace motif::cli
