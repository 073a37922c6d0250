#include "engine/cli/numeric_options.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <typeinfo>

#include "engine/pipeline/option_table.h"

namespace motif::cli {
namespace {

namespace po = boost::program_options;

// Frame rates: capture systems record at up to a few thousand frames a second; 5e7 made the
// resampler allocate until the process was killed.
constexpr double kMaxFps = 10000;
// A count that only caps what is printed, or a frame or column number checked against the data
// when it is read (exit 13): any value of its type is harmless.
constexpr double kAny32 = 4294967295.0;
constexpr double kAny64 = 18446744073709551615.0;
// Frames per archive block: a block is read and written whole, 65,536 frames of 31 joints are
// 32 MB raw; more only makes the buffers bigger (the format itself allows 2^22).
constexpr double kMaxBlockFrames = 65536;

FlagRange Range(const char* command, const char* flag, double min, double max) {
  return {command, flag, min, max, false, false, false};
}
// (min, max]: the least value itself is refused (a length of 0 seconds).
FlagRange Above(const char* command, const char* flag, double min, double max) {
  return {command, flag, min, max, true, false, false};
}
// 0 ("not given": the take's own rate) or a frame rate.
FlagRange RateOrZero(const char* command, const char* flag) {
  return {command, flag, 1, kMaxFps, false, true, false};
}
// "auto" or a count in [min, max], given as text.
FlagRange AutoOr(const char* command, const char* flag, double min, double max) {
  return {command, flag, min, max, false, false, true};
}

void AddIngestRanges(std::vector<FlagRange>* table) {
  // reindex: a file must be unchanged this long before it is imported; a year is already never.
  table->push_back(Range("reindex", "min-age", 0, 365 * 86400.0));
  table->push_back(RateOrZero("reindex", "fps"));
  table->push_back(RateOrZero("import", "fps"));
  table->push_back(RateOrZero("import", "bvh-fps"));
  table->push_back(Range("import", "amc-fps", 1, kMaxFps));  // an AMC file has no rate of its own
  table->push_back(Range("import", "block-frames", 1, kMaxBlockFrames));
  table->push_back(Range("info", "clips", 0, kAny64));
  table->push_back(Range("export", "start", 0, kAny64));
  table->push_back(Range("export", "end", 0, kAny64));
}

void AddSynthRanges(std::vector<FlagRange>* table) {
  // The largest archive the project measures (10^8 frames, about 7 GB), as --synth-frames.
  table->push_back(Range("synth", "frames", 1, 1e8));
  table->push_back(Range("synth", "motifs", 0, 10000));  // as --synth-motifs
  table->push_back(Range("synth", "fps", 1, kMaxFps));
  // A clip of up to a day, a motif of up to an hour: the synthesizer's own limits are 10^9
  // and 10^8 frames, which these stay within at 10,000 frames a second.
  table->push_back(Above("synth", "clip-seconds-min", 0, 86400));
  table->push_back(Above("synth", "clip-seconds-max", 0, 86400));
  table->push_back(Above("synth", "motif-seconds-min", 0, 3600));
  table->push_back(Above("synth", "motif-seconds-max", 0, 3600));
  // A motif repeats; how many instances fit is bounded by --frames (half of them at most).
  table->push_back(Range("synth", "instances-min", 2, 10000));
  table->push_back(Range("synth", "instances-max", 2, 10000));
  // The synthesizer's limits: beyond 20 degrees the noise swamps the planted motion.
  table->push_back(Range("synth", "noise-degrees", 0, 20));
  table->push_back(Range("synth", "background-variation", 0, 20));
  table->push_back(Range("synth", "gap-seconds", 0, 3600));
  table->push_back(Range("synth", "block-frames", 1, kMaxBlockFrames));
}

void AddTrellisAndReportRanges(std::vector<FlagRange>* table) {
  // Columns audited by an exact search each; more than an archive has are capped to it.
  table->push_back(Range("trellis", "sample", 1, 1e9));
  table->push_back(Range("inspect-trellis", "column", 0, kAny64));
  table->push_back(Range("report", "keyframes", 1, 50));  // figures side by side in one row
  table->push_back(Range("report", "instances", 0, 10000));
  table->push_back(Range("report", "eager", 0, 1e6));
  table->push_back(Range("score", "motifs", 0, kAny32));
  table->push_back(Range("export-motif", "motif", 0, kAny32));
}

void AddWordsRanges(std::vector<FlagRange>* table) {
  table->push_back(Range("words", "motifs", 1, 65535));      // the words builder's limit
  table->push_back(Range("words", "word-frames", 1, 1024));  // kMaxWordFrames (word_grid.h)
  table->push_back(Range("words", "stride", 1, 1e6));        // frames between word starts
  // Words are resampled to this rate: 99999999999 allocated until std::bad_alloc.
  table->push_back(Above("words", "word-fps", 0, 1000));
  table->push_back(Range("words", "epochs", 0, 10000));    // 0: the untrained embedding
  table->push_back(Range("words", "pool-words", 1, 1e9));  // capped by the archive's words
  table->push_back(Range("words", "warp-copies", 0, 64));  // the word pool's limit
  table->push_back(Range("words", "held-out", 0, 0.9));    // the rest trains the embedding
  table->push_back(Range("words", "batch", 1, 65536));
  table->push_back(Above("words", "learning-rate", 0, 1));  // Adam diverges beyond
  // Embeddings lie on the unit sphere: no squared distance exceeds 4, so a larger margin only
  // makes every triplet count.
  table->push_back(Above("words", "margin", 0, 4));
  table->push_back(Range("words", "dims", 1, 4096));  // the network's limit
  // Both convolutions have this many channels; conv2 holds channels^2 x 3 weights (3 M at 1,024).
  table->push_back(Range("words", "channels", 1, 1024));
}

void AddSignatureRanges(std::vector<FlagRange>* table) {
  table->push_back(Range("search", "start", 0, kAny64));  // within the clip: checked there
  table->push_back(Range("search", "end", 0, kAny64));
  table->push_back(Range("search", "top", 1, 100000));
  // MDS dimensions, neighbours and matches are capped by the takes there are; the bounds only
  // refuse what no archive needs.
  table->push_back(AutoOr("classify", "groups", 1, 1e6));  // k-means groups, as mine's --groups
  table->push_back(Range("classify", "dims", 1, 1000));
  table->push_back(Range("classify", "knn", 1, 10000));
  table->push_back(Range("classify", "top", 1, 100000));
  table->push_back(Range("classify", "dtw-step", 1, 100000));
  table->push_back(Range("segment", "window", 1, 10000));
  table->push_back(Range("segment", "knn", 1, 10000));
  table->push_back(Range("segment", "dtw-step", 1, 100000));
  table->push_back(AutoOr("segment", "groups", 1, 1e6));  // unsupervised groups, as classify's
  // graph: a walk of up to a day; a transition's window of up to 5 s, a piece of up to an hour.
  table->push_back(Above("graph", "seconds", 0, 86400));
  table->push_back(Range("graph", "min-piece", 0, 3600));
  table->push_back(Above("graph", "window", 0, 5));
}

std::vector<FlagRange> MakeRanges() {
  std::vector<FlagRange> table;
  AddIngestRanges(&table);
  AddSynthRanges(&table);
  AddTrellisAndReportRanges(&table);
  AddWordsRanges(&table);
  AddSignatureRanges(&table);
  return table;
}

bool IsUnsigned(const std::type_info& type) {
  return type == typeid(uint32_t) || type == typeid(uint64_t) || type == typeid(size_t) ||
         type == typeid(uint16_t);
}

bool IsFloating(const std::type_info& type) {
  return type == typeid(double) || type == typeid(float);
}

double AsDouble(const boost::any& value) {
  const std::type_info& type = value.type();
  if (type == typeid(double)) return boost::any_cast<double>(value);
  if (type == typeid(float)) return boost::any_cast<float>(value);
  if (type == typeid(uint16_t)) return boost::any_cast<uint16_t>(value);
  if (type == typeid(uint32_t)) return boost::any_cast<uint32_t>(value);
  if (type == typeid(uint64_t)) return static_cast<double>(boost::any_cast<uint64_t>(value));
  return static_cast<double>(boost::any_cast<size_t>(value));
}

Status Bad(const std::string& flag, const std::string& given, const std::string& rule) {
  return Status::InvalidArgument("--" + flag + " must be " + rule + ", not '" + given + "'");
}

std::string RangeRule(const FlagRange& range, bool whole) {
  if (range.max == kAny64) return whole ? "a whole number >= 0" : "a number >= 0";
  const std::string interval = std::string(range.min_exclusive ? "(" : "[") +
                               FormatOptionNumber(range.min) + ", " +
                               FormatOptionNumber(range.max) + "]";
  return std::string(range.zero_allowed ? "0 (not given) or " : "") +
         (whole ? "a whole number in " : "a number in ") + interval;
}

bool InRange(const FlagRange& range, double number) {
  if (range.zero_allowed && number == 0) return true;
  const bool below = range.min_exclusive ? number <= range.min : number < range.min;
  return std::isfinite(number) && !below && number <= range.max;
}

// A text flag that is "auto" or a count (FlagRange::auto_allowed).
Status CheckAutoOrCount(const FlagRange& range, const std::string& given) {
  if (given == "auto") return Status::Ok();
  char* end = nullptr;
  const double number = std::strtod(given.c_str(), &end);
  const bool whole =
      !given.empty() && *end == '\0' && given.find_first_not_of("0123456789") == std::string::npos;
  if (whole && InRange(range, number)) return Status::Ok();
  return Bad(range.flag, given, "auto or " + RangeRule(range, true));
}

Status CheckOne(const std::string& command, const std::string& flag, const std::string& given,
                const boost::any& value) {
  const std::type_info& type = value.type();
  if (type == typeid(std::string)) {
    const FlagRange* range = FindFlagRange(command, flag);
    return range != nullptr && range->auto_allowed ? CheckAutoOrCount(*range, given) : Status::Ok();
  }
  const bool whole = IsUnsigned(type);
  if (!whole && !IsFloating(type)) return Status::Ok();
  const FlagRange* range = FindFlagRange(command, flag);
  // boost reads "-1" as 4294967295 for an unsigned flag: the text tells.
  const bool negative = whole && given.find('-') != std::string::npos;
  if (range != nullptr && (negative || !InRange(*range, AsDouble(value)))) {
    return Bad(flag, given, RangeRule(*range, whole));
  }
  if (negative) return Bad(flag, given, "a whole number >= 0");
  if (!whole && !std::isfinite(AsDouble(value))) return Bad(flag, given, "a finite number");
  return Status::Ok();
}

}  // namespace

const std::vector<FlagRange>& FlagRanges() {
  static const std::vector<FlagRange> table = MakeRanges();
  return table;
}

const FlagRange* FindFlagRange(const std::string& command, const std::string& flag) {
  for (const FlagRange& range : FlagRanges()) {
    if (command == range.command && flag == range.flag) return &range;
  }
  return nullptr;
}

Status CheckNumericOptions(const std::string& command, const po::parsed_options& parsed,
                           const po::variables_map& vm) {
  for (const po::option& option : parsed.options) {
    if (option.position_key != -1 || option.value.empty() || !vm.count(option.string_key)) {
      continue;  // positional, a switch without a value, or not stored
    }
    const boost::any& value = vm[option.string_key].value();
    for (const std::string& given : option.value) {
      Status status = CheckOne(command, option.string_key, given, value);
      if (!status.ok()) return status;
    }
  }
  return Status::Ok();
}

}  // namespace motif::cli
