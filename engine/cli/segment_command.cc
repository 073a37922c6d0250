// motifmine segment ARCHIVE [--labels LABELS.tsv] [--clip NAME ...] --out DIR: temporal
// segmentation of takes by their motion signatures (take_segmentation.h), supervised with the
// labels of other takes or unsupervised, written as DIR/segments.json and DIR/segments.html.
// The words files are built first (as `motifmine words` with its defaults) when missing.
#include <chrono>
#include <cstdio>
#include <map>
#include <set>

#include "common/file_util.h"
#include "engine/cli/cli_common.h"
#include "engine/cli/table_options.h"
#include "engine/cli/take_labels.h"
#include "engine/cli/words_on_demand.h"
#include "engine/report/segments_html.h"
#include "engine/signature/take_retrieval.h"
#include "engine/words/take_segmentation.h"
#include "engine/words/word_model.h"

namespace motif::cli {
namespace {

namespace po = boost::program_options;

using ClipIndex = std::map<std::string, uint32_t>;  // archive clip by name

ClipIndex IndexClips(const FrameFileReader& reader) {
  ClipIndex index;
  for (uint32_t clip = 0; clip < reader.clips().size(); ++clip) {
    index[reader.clips()[clip].name] = clip;
  }
  return index;
}

// The clips named by --clip (every clip when none), in the order given.
Result<std::vector<uint32_t>> ClipsAskedFor(const FrameFileReader& reader, const ClipIndex& index,
                                            const std::vector<std::string>& names) {
  std::vector<uint32_t> clips;
  if (names.empty()) {
    for (uint32_t clip = 0; clip < reader.clips().size(); ++clip) clips.push_back(clip);
    return clips;
  }
  for (const std::string& name : names) {
    const auto found = index.find(name);
    if (found == index.end()) {
      return Status::NotFound("--clip: no clip named '" + name + "' (motifmine info lists them)");
    }
    clips.push_back(found->second);
  }
  return clips;
}

// Per archive clip its label index, and the sorted label names, from the labels file.
void IndexLabels(const FrameFileReader& reader, const ClipIndex& clip_of, const TakeLabels& labels,
                 std::vector<uint32_t>* clip_labels, std::vector<std::string>* names,
                 uint64_t* unknown) {
  std::set<std::string> distinct;
  for (const auto& [clip, label] : labels.by_clip) {
    if (clip_of.count(clip)) distinct.insert(label);
  }
  names->assign(distinct.begin(), distinct.end());
  clip_labels->assign(reader.clips().size(), kUnlabelled);
  *unknown = 0;
  for (const auto& [clip, label] : labels.by_clip) {
    const auto found = clip_of.find(clip);
    if (found == clip_of.end()) {
      ++*unknown;
      continue;
    }
    (*clip_labels)[found->second] = static_cast<uint32_t>(
        std::lower_bound(names->begin(), names->end(), label) - names->begin());
  }
}

std::string SegmentMethod(const Segmentation& result) {
  if (!result.supervised) return "unsupervised";
  if (result.distance == "dtw") return "supervised, kNN by DTW over the windows' frames";
  return "supervised, kNN by the EMD between " + result.signature + " signatures";
}

void PrintSegmentSummary(const Segmentation& result, const FrameFileReader& reader,
                         const std::string& archive, double seconds,
                         const WordsReaderOutput& output) {
  uint64_t segments = 0;
  for (const SegmentedTake& take : result.takes) segments += take.segments.size();
  std::printf("motifmine segment: %s (%zu takes, %s)\n", archive.c_str(), result.takes.size(),
              SegmentMethod(result).c_str());
  if (result.supervised) {
    std::printf("  method       %u-NN over windows of %u words: %s windows of %s labelled takes\n",
                result.knn, result.window, WithCommas(result.reference_windows).c_str(),
                WithCommas(result.reference_takes).c_str());
  } else {
    std::printf("  method       %s, change score over %u words either side, threshold %.4f\n",
                result.signature == "words" ? "affinity profiles of the words"
                                            : "TF-IDF signatures over the motifs",
                result.window, result.threshold);
    std::printf("  grouping     %s linkage within %.4f\n", result.linkage.c_str(),
                result.group_threshold);
  }
  std::printf("  segments     %s over %zu labels\n", WithCommas(segments).c_str(),
              result.label_names.size());
  for (const SegmentedTake& take : result.takes) {
    std::printf("    %-20s %8s frames %4zu segments\n", reader.clips()[take.clip].name.c_str(),
                WithCommas(reader.clips()[take.clip].frame_count).c_str(), take.segments.size());
  }
  if (!result.skipped_clips.empty()) {
    std::printf("  skipped      %zu takes shorter than one motion word\n",
                result.skipped_clips.size());
  }
  std::printf("  time         %.2fs\n", seconds);
  std::printf("  wrote        %s, %s\n", output.json_path.c_str(), output.html_path.c_str());
}

// The command line of `segment`, read back and checked.
struct SegmentCommandOptions {
  std::string archive;
  std::string distance;     // emd or dtw
  std::string labels_path;  // empty: unsupervised
  std::string signature;    // "", words or motifs
  std::string weights_path;
  std::vector<std::string> clip_names;  // empty: every take
  uint64_t seed = 1;                    // of the words build, when the files are missing
  SegmentOptions segment;               // all but the progress callback
  WordsReaderOutput output;
  ProgressMode progress_mode = ProgressMode::kAuto;
};

void AddSegmentOptions(CommandSpec& spec) {
  spec.name = "segment";
  spec.usage =
      "motifmine segment ARCHIVE [--labels LABELS.tsv] [--clip NAME ...] --out DIR "
      "[--distance emd|dtw] [--signature words|motifs] [--window W] [--knn K] [--groups K]";
  spec.summary =
      "Cuts takes into segments of one activity by their motion signatures. With --labels (a\n"
      "TSV of clip and label, as classify reads), each motion word takes the majority label of\n"
      "the K nearest windows of W words of the labelled takes (EMD between the windows'\n"
      "signatures: by default their bags of words, compared word with word by DTW; a take\n"
      "never votes for itself), and equal neighbouring labels merge into segments. Without,\n"
      "boundaries go where the words before and after differ most, and segments of one\n"
      "activity, in any take, share a group (by default the words' affinity profiles, which\n"
      "depend on no seed; --groups K sets the number of groups). Segments the takes named by\n"
      "--clip (default: every take). Motif signatures need the words files and build them\n"
      "first (as `motifmine words`) when they are missing; word signatures and dtw only cut\n"
      "the words.\n"
      "Writes DIR/segments.json and DIR/segments.html.";
  SegmentOptions defaults;
  spec.options.add_options()("labels", po::value<std::string>()->default_value(""),
                             "labels of takes: a TSV file of clip<TAB>label lines")(
      "clip", po::value<std::vector<std::string>>()->composing(),
      "a take to segment (repeatable; default: every take)")(
      "distance", po::value<std::string>()->default_value("emd"),
      "emd (signatures) or dtw (the windows' frames, a baseline; needs --labels)")(
      "signature", po::value<std::string>()->default_value(""),
      "with emd, what a window's signature is: words (the default; with --labels every word "
      "its own bin, DTW between words as ground distance; without, the words' affinity "
      "profiles) or motifs (the paper's TF-IDF histogram over the motifs)")(
      "window", po::value<uint32_t>()->default_value(defaults.window), "words per window")(
      "knn", po::value<uint32_t>()->default_value(defaults.knn), "neighbours of the vote")(
      "neighbours", po::value<std::string>()->default_value("windows"),
      "what the K neighbours are: windows (the K nearest windows) or takes (the K nearest "
      "labelled takes, each at its nearest window)")(
      "dtw-step", po::value<uint32_t>()->default_value(defaults.dtw_step),
      "dtw: compare every n-th frame")(
      "groups", po::value<std::string>()->default_value("auto"),
      "without --labels: the number of groups, or auto (chosen from the segments themselves; "
      "docs/design/signatures.md, section 11)");
  AddTableFlags(spec, {"weights", "seed"});
  AddWordsReaderOptions(spec, "PREFIX.mwm and PREFIX.mws", "segments");
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
}

// --distance, --labels and --signature together: InvalidArgument naming the flag.
Status CheckSegmentMethod(const SegmentCommandOptions& options) {
  const std::string& distance = options.distance;
  const std::string& signature = options.signature;
  if (distance != "emd" && distance != "dtw") {
    return Status::InvalidArgument("--distance must be emd or dtw, not '" + distance + "'");
  }
  if (distance == "dtw" && options.labels_path.empty()) {
    return Status::InvalidArgument("--distance dtw needs --labels (it is supervised only)");
  }
  if (!signature.empty() && signature != "words" && signature != "motifs") {
    return Status::InvalidArgument("--signature must be words or motifs, not '" + signature + "'");
  }
  if (!signature.empty() && distance == "dtw") {
    return Status::InvalidArgument("--signature needs --distance emd (dtw compares frames)");
  }
  return Status::Ok();
}

// InvalidArgument naming the flag for a bad value; IOError if the output folder cannot be made.
Result<SegmentCommandOptions> ReadSegmentOptions(const po::variables_map& vm) {
  SegmentCommandOptions options;
  options.archive = vm["archive"].as<std::string>();
  options.distance = vm["distance"].as<std::string>();
  options.labels_path = vm["labels"].as<std::string>();
  options.signature = vm["signature"].as<std::string>();
  MOTIF_RETURN_IF_ERROR(CheckSegmentMethod(options));
  SegmentOptions& segment = options.segment;
  segment.signature =
      options.signature == "motifs" ? WindowSignature::kMotifs : WindowSignature::kWords;
  segment.window = vm["window"].as<uint32_t>();
  segment.knn = vm["knn"].as<uint32_t>();
  segment.dtw_step = vm["dtw-step"].as<uint32_t>();
  const std::string groups = vm["groups"].as<std::string>();
  if (groups != "auto") {
    if (!options.labels_path.empty()) {
      return Status::InvalidArgument("--groups is for segmenting without --labels");
    }
    MOTIF_RETURN_IF_ERROR(ParseGroups(groups, &segment.groups));
  }
  const std::string neighbours = vm["neighbours"].as<std::string>();
  if (neighbours != "windows" && neighbours != "takes") {
    return Status::InvalidArgument("--neighbours must be windows or takes, not '" + neighbours +
                                   "'");
  }
  segment.one_per_take = neighbours == "takes";
  motifmine::MineOptions table;
  ReadTableFlags(vm, {"weights", "seed", "threads"}, &table);
  segment.threads = table.threads;
  MOTIF_ASSIGN_OR_RETURN(options.output, WordsReaderOutputFrom(vm, options.archive, "segments"));
  options.clip_names =
      vm.count("clip") ? vm["clip"].as<std::vector<std::string>>() : std::vector<std::string>{};
  options.weights_path = table.weights_path;
  options.seed = table.seed;
  options.progress_mode = ProgressModeFrom(vm);
  return options;
}

// The archive, the takes to segment and the labels.
struct SegmentInputs {
  std::unique_ptr<FrameFileReader> reader;
  ClipIndex clip_index;
  std::vector<uint32_t> clips;
  TakeLabels labels;
};

Status OpenSegmentInputs(const SegmentCommandOptions& options, SegmentInputs* inputs) {
  MOTIF_ASSIGN_OR_RETURN(inputs->reader, FrameFileReader::Open(options.archive));
  inputs->clip_index = IndexClips(*inputs->reader);
  MOTIF_ASSIGN_OR_RETURN(inputs->clips,
                         ClipsAskedFor(*inputs->reader, inputs->clip_index, options.clip_names));
  if (!options.labels_path.empty()) {
    MOTIF_ASSIGN_OR_RETURN(inputs->labels, ReadTakeLabels(options.labels_path));
  }
  return Status::Ok();
}

// Motif signatures need the words files (built when missing); word signatures and the DTW
// baseline need only where the words lie, not their embedding.
Result<LoadedWords> LoadSegmentWords(const SegmentCommandOptions& options,
                                     const FrameFileReader& reader, ProgressReporter& progress) {
  const WordsPaths paths = DefaultWordsPaths(options.output.prefix_archive);
  const bool needs_motifs = options.distance == "emd" && options.signature == "motifs";
  return needs_motifs ? LoadOrBuildWords(options.archive, reader, paths, options.seed,
                                         options.segment.threads, progress)
                      : LoadWordsOrGrid(options.archive, reader, paths, progress);
}

// What the supervised segmentation needs besides the words: the labels per clip, the joint
// weights (in *segment) and, for dtw, the archive's pose features.
struct SupervisedSegmentInputs {
  std::vector<uint32_t> clip_labels;
  std::vector<std::string> label_names;
  std::optional<PoseFeatures> features;
};

Status PrepareSupervisedSegments(const SegmentCommandOptions& options, const SegmentInputs& inputs,
                                 ProgressReporter& progress, SupervisedSegmentInputs* supervised,
                                 SegmentOptions* segment) {
  uint64_t unknown = 0;
  IndexLabels(*inputs.reader, inputs.clip_index, inputs.labels, &supervised->clip_labels,
              &supervised->label_names, &unknown);
  if (unknown > 0) {
    progress.Note(std::to_string(unknown) + " labelled clips of " + options.labels_path +
                  " are not clips of the archive: ignored");
  }
  MOTIF_ASSIGN_OR_RETURN(std::vector<float> weights,
                         LoadDistanceWeights(inputs.reader->skeleton(), options.weights_path));
  segment->joint_weights = weights;
  if (options.distance == "dtw") {
    MOTIF_ASSIGN_OR_RETURN(supervised->features,
                           PoseFeatures::FromArchive(*inputs.reader, weights));
  }
  return Status::Ok();
}

// Segments the takes, supervised with the labels or not. The progress stages end with the
// segmentation (not after an error in preparing the supervised one, which stops the command).
Result<Segmentation> SegmentTakes(const SegmentCommandOptions& options, const SegmentInputs& inputs,
                                  const LoadedWords& words, ProgressReporter& progress) {
  SegmentOptions segment = options.segment;
  segment.progress = [&progress](const std::string& stage, uint64_t done, uint64_t total) {
    // windows: takes scored; profiles: words; groups: segments; vote: windows.
    const char* unit = stage == "windows"    ? "takes"
                       : stage == "profiles" ? "words"
                       : stage == "groups"   ? "segments"
                                             : "windows";
    progress.StageUpdate(stage, done, total, unit);
  };
  Result<Segmentation> result = Status::InvalidArgument("not segmented");
  if (options.labels_path.empty()) {
    result = SegmentUnsupervised(*inputs.reader, words, inputs.clips, segment);
  } else {
    SupervisedSegmentInputs supervised;
    MOTIF_RETURN_IF_ERROR(
        PrepareSupervisedSegments(options, inputs, progress, &supervised, &segment));
    result = SegmentSupervised(*inputs.reader, words, inputs.clips, supervised.clip_labels,
                               supervised.label_names,
                               supervised.features ? &*supervised.features : nullptr, segment);
  }
  progress.EndStages();
  return result;
}

Status WriteSegmentFiles(const SegmentCommandOptions& options, const FrameFileReader& reader,
                         const LoadedWords& words, const Segmentation& result, double seconds) {
  nlohmann::json json = SegmentsJson(result, reader, options.archive);
  json["seconds"] = seconds;
  MOTIF_RETURN_IF_ERROR(AtomicWriteFile(options.output.json_path, json.dump(2) + "\n"));
  SegmentsPageInfo info{options.archive, options.labels_path, words.motifs.motif_count(), seconds};
  return WriteSegmentsHtml(options.output.html_path, result, reader, info);
}

}  // namespace

int RunSegment(const std::vector<std::string>& args) {
  CommandSpec spec;
  AddSegmentOptions(spec);
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const auto fail = [](const Status& status) { return ReportError("segment", status); };
  Result<SegmentCommandOptions> options = ReadSegmentOptions(vm);
  if (!options.ok()) return fail(options.status());
  SegmentInputs inputs;
  if (Status status = OpenSegmentInputs(*options, &inputs); !status.ok()) return fail(status);

  ProgressReporter progress(options->progress_mode);
  Result<LoadedWords> words = LoadSegmentWords(*options, *inputs.reader, progress);
  if (!words.ok()) return fail(words.status());
  const auto start = std::chrono::steady_clock::now();
  Result<Segmentation> result = SegmentTakes(*options, inputs, *words, progress);
  if (!result.ok()) return fail(result.status());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (Status status = WriteSegmentFiles(*options, *inputs.reader, *words, *result, seconds);
      !status.ok()) {
    return fail(status);
  }
  PrintSegmentSummary(*result, *inputs.reader, options->archive, seconds, options->output);
  return kExitOk;
}

}  // namespace motif::cli
