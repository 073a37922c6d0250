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

std::string Method(const Segmentation& result) {
  if (!result.supervised) return "unsupervised";
  if (result.distance == "dtw") return "supervised, kNN by DTW over the windows' frames";
  return "supervised, kNN by the EMD between " + result.signature + " signatures";
}

void PrintSummary(const Segmentation& result, const FrameFileReader& reader,
                  const std::string& archive, double seconds, const WordsReaderOutput& output) {
  uint64_t segments = 0;
  for (const SegmentedTake& take : result.takes) segments += take.segments.size();
  std::printf("motifmine segment: %s (%zu takes, %s)\n", archive.c_str(), result.takes.size(),
              Method(result).c_str());
  if (result.supervised) {
    std::printf("  method       %u-NN over windows of %u words: %s windows of %s labelled takes\n",
                result.knn, result.window, WithCommas(result.reference_windows).c_str(),
                WithCommas(result.reference_takes).c_str());
  } else {
    std::printf(
        "  method       change score over %u words either side, threshold %.4f (mean + "
        "1 sd of the scores)\n",
        result.window, result.threshold);
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

}  // namespace

int RunSegment(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "segment";
  spec.usage =
      "motifmine segment ARCHIVE [--labels LABELS.tsv] [--clip NAME ...] --out DIR "
      "[--distance emd|dtw] [--signature words|motifs] [--window W] [--knn K]";
  spec.summary =
      "Cuts takes into segments of one activity by their motion signatures. With --labels (a\n"
      "TSV of clip and label, as classify reads), each motion word takes the majority label of\n"
      "the K nearest windows of W words of the labelled takes (EMD between the windows'\n"
      "signatures: by default their bags of words, compared word with word by DTW; a take\n"
      "never votes for itself), and equal neighbouring labels merge into segments. Without,\n"
      "boundaries go where the motif signatures before and after differ most, and segments\n"
      "are grouped by signature. Segments the takes named by --clip (default: every take).\n"
      "Motif signatures need the words files and build them first (as `motifmine words`)\n"
      "when they are missing; word signatures and dtw only cut the words.\n"
      "Writes DIR/segments.json and DIR/segments.html.";
  SegmentOptions defaults;
  spec.options.add_options()("labels", po::value<std::string>()->default_value(""),
                             "labels of takes: a TSV file of clip<TAB>label lines")(
      "clip", po::value<std::vector<std::string>>()->composing(),
      "a take to segment (repeatable; default: every take)")(
      "distance", po::value<std::string>()->default_value("emd"),
      "emd (signatures) or dtw (the windows' frames, a baseline; needs --labels)")(
      "signature", po::value<std::string>()->default_value(""),
      "with --labels and emd, what a window's signature is: words (the default: every word its "
      "own bin, DTW between words as ground distance) or motifs (the paper's TF-IDF histogram "
      "over the motifs); without --labels it is motifs")(
      "window", po::value<uint32_t>()->default_value(defaults.window), "words per window")(
      "knn", po::value<uint32_t>()->default_value(defaults.knn), "neighbours of the vote")(
      "neighbours", po::value<std::string>()->default_value("windows"),
      "what the K neighbours are: windows (the K nearest windows) or takes (the K nearest "
      "labelled takes, each at its nearest window)")(
      "dtw-step", po::value<uint32_t>()->default_value(defaults.dtw_step),
      "dtw: compare every n-th frame")("weights", po::value<std::string>()->default_value(""),
                                       "dtw and word signatures: per-joint weights file "
                                       "(default: the skeleton's)")(
      "seed", po::value<uint64_t>()->default_value(1),
      "seed of the words build when the words files are missing");
  AddWordsReaderOptions(spec, "PREFIX.mwm and PREFIX.mws", "segments");
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const auto fail = [](const Status& status) { return ReportError("segment", status); };
  const std::string archive = vm["archive"].as<std::string>();
  const std::string distance = vm["distance"].as<std::string>();
  const std::string labels_path = vm["labels"].as<std::string>();
  if (distance != "emd" && distance != "dtw") {
    return fail(Status::InvalidArgument("--distance must be emd or dtw, not '" + distance + "'"));
  }
  if (distance == "dtw" && labels_path.empty()) {
    return fail(Status::InvalidArgument("--distance dtw needs --labels (it is supervised only)"));
  }
  const std::string signature = vm["signature"].as<std::string>();
  if (!signature.empty() && signature != "words" && signature != "motifs") {
    return fail(
        Status::InvalidArgument("--signature must be words or motifs, not '" + signature + "'"));
  }
  if (signature == "words" && (labels_path.empty() || distance == "dtw")) {
    return fail(Status::InvalidArgument(
        "--signature words needs --labels and --distance emd (without --labels, segments are "
        "found and grouped by motif signatures)"));
  }
  SegmentOptions options;
  options.signature = signature == "motifs" ? WindowSignature::kMotifs : WindowSignature::kWords;
  options.window = vm["window"].as<uint32_t>();
  options.knn = vm["knn"].as<uint32_t>();
  options.dtw_step = vm["dtw-step"].as<uint32_t>();
  const std::string neighbours = vm["neighbours"].as<std::string>();
  if (neighbours != "windows" && neighbours != "takes") {
    return fail(
        Status::InvalidArgument("--neighbours must be windows or takes, not '" + neighbours + "'"));
  }
  options.one_per_take = neighbours == "takes";
  options.threads = vm["threads"].as<int>();
  if (options.window == 0 || options.knn == 0 || options.dtw_step == 0) {
    return fail(Status::InvalidArgument("--window, --knn and --dtw-step must be at least 1"));
  }
  Result<WordsReaderOutput> output = WordsReaderOutputFrom(vm, archive, "segments");
  if (!output.ok()) return fail(output.status());
  Result<std::unique_ptr<FrameFileReader>> reader = FrameFileReader::Open(archive);
  if (!reader.ok()) return fail(reader.status());
  const std::vector<std::string> names =
      vm.count("clip") ? vm["clip"].as<std::vector<std::string>>() : std::vector<std::string>{};
  const ClipIndex clip_index = IndexClips(**reader);
  Result<std::vector<uint32_t>> clips = ClipsAskedFor(**reader, clip_index, names);
  if (!clips.ok()) return fail(clips.status());
  TakeLabels labels;
  if (!labels_path.empty()) {
    Result<TakeLabels> read = ReadTakeLabels(labels_path);
    if (!read.ok()) return fail(read.status());
    labels = std::move(read.value());
  }

  ProgressReporter progress(ProgressModeFrom(vm));
  const WordsPaths paths = DefaultWordsPaths(output->prefix_archive);
  // Word signatures and the DTW baseline need only where the words lie, not their embedding.
  const bool needs_motifs = labels_path.empty() || (distance == "emd" && signature == "motifs");
  Result<LoadedWords> words =
      needs_motifs ? LoadOrBuildWords(archive, **reader, paths, vm["seed"].as<uint64_t>(),
                                      options.threads, progress)
                   : LoadWordsOrGrid(archive, **reader, paths, progress);
  if (!words.ok()) return fail(words.status());

  options.progress = [&](const std::string& stage, uint64_t done, uint64_t total) {
    progress.StageUpdate(stage, done, total, stage == "windows" ? "takes" : "windows");
  };
  const auto start = std::chrono::steady_clock::now();
  Result<Segmentation> result = Status::InvalidArgument("not segmented");
  if (labels_path.empty()) {
    result = SegmentUnsupervised(**reader, *words, *clips, options);
  } else {
    std::vector<uint32_t> clip_labels;
    std::vector<std::string> label_names;
    uint64_t unknown = 0;
    IndexLabels(**reader, clip_index, labels, &clip_labels, &label_names, &unknown);
    if (unknown > 0) {
      progress.Note(std::to_string(unknown) + " labelled clips of " + labels_path +
                    " are not clips of the archive: ignored");
    }
    std::optional<PoseFeatures> features;
    Result<std::vector<float>> weights =
        LoadDistanceWeights((*reader)->skeleton(), vm["weights"].as<std::string>());
    if (!weights.ok()) return fail(weights.status());
    options.joint_weights = *weights;
    if (distance == "dtw") {
      Result<PoseFeatures> computed = PoseFeatures::FromArchive(**reader, *weights);
      if (!computed.ok()) return fail(computed.status());
      features = std::move(computed.value());
    }
    result = SegmentSupervised(**reader, *words, *clips, clip_labels, label_names,
                               features ? &*features : nullptr, options);
  }
  progress.EndStages();
  if (!result.ok()) return fail(result.status());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::json json = SegmentsJson(*result, **reader, archive);
  json["seconds"] = seconds;
  if (Status status = AtomicWriteFile(output->json_path, json.dump(2) + "\n"); !status.ok()) {
    return fail(status);
  }
  SegmentsPageInfo info{archive, labels_path, words->motifs.motif_count(), seconds};
  if (Status status = WriteSegmentsHtml(output->html_path, *result, **reader, info); !status.ok()) {
    return fail(status);
  }
  PrintSummary(*result, **reader, archive, seconds, *output);
  return kExitOk;
}

}  // namespace motif::cli
