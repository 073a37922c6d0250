// motifmine classify ARCHIVE [--labels FILE.tsv] [...]: the takes of an archive classified by
// their motion signatures (unsupervised: MDS and k-means; supervised: leave-one-out kNN with the
// labels, and whole-take retrieval precision), or by a baseline distance.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "common/file_util.h"
#include "engine/cli/cli_common.h"
#include "engine/cli/table_options.h"
#include "engine/cli/take_labels.h"
#include "engine/distance/pose_features.h"
#include "engine/report/words_report_html.h"
#include "engine/signature/signature_matrix.h"
#include "engine/signature/take_dtw.h"
#include "engine/signature/take_movement.h"
#include "engine/signature/word_stream.h"
#include "engine/words/take_classification.h"
#include "engine/words/word_model.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

// The command line of `classify`, read back and checked.
struct ClassifyCommandOptions {
  std::string archive;
  std::string distance_name;  // emd, emd-tf, dtw or movement
  std::string labels_path;    // empty: no labels
  std::string weights_path;   // dtw's per-joint weights ("": the skeleton's)
  uint32_t dtw_step = 1;
  ClassifyOptions classify;
  WordsReaderOutput output;
  ProgressMode progress_mode = ProgressMode::kAuto;

  bool dtw() const { return distance_name == "dtw"; }
  bool movement() const { return distance_name == "movement"; }
  bool needs_words() const { return !dtw() && !movement(); }
};

void AddClassifyOptions(CommandSpec& spec) {
  spec.name = "classify";
  spec.usage =
      "motifmine classify ARCHIVE [--labels FILE.tsv] [--distance emd|emd-tf|dtw|movement] "
      "[--groups G] [--knn K] [--top T] [--out DIR]";
  spec.summary =
      "Classifies the takes of ARCHIVE (those with at least one motion word) by the Earth\n"
      "Mover's Distance between their motion signatures (run `motifmine words` first).\n"
      "Unsupervised: classical MDS of the distance matrix, then k-means into G groups.\n"
      "Supervised (--labels, a TSV of clip and label): leave-one-out k-nearest-neighbour\n"
      "accuracy, and whole-take retrieval precision at T. --distance emd-tf compares the\n"
      "signatures without TF-IDF, dtw the takes' frames by dynamic time warping (baselines);\n"
      "movement compares what moves, how, and where the body goes, blind to the posture,\n"
      "amplitude and tempo a style changes (no words files needed).\n"
      "Writes DIR/classify.json and DIR/classify.html.";
  ClassifyOptions defaults;
  spec.options.add_options()("labels", po::value<std::string>()->default_value(""),
                             "labels of takes: a TSV file of clip<TAB>label lines")(
      "distance", po::value<std::string>()->default_value("emd"),
      "emd (TF-IDF signatures), emd-tf (term frequencies only), dtw (frames) or movement "
      "(what moves and how, style-blind)")(
      "groups", po::value<std::string>()->default_value("auto"),
      "unsupervised groups, or auto (the number of labels, else 8)")(
      "dims", po::value<uint32_t>()->default_value(defaults.dims), "MDS dimensions")(
      "knn", po::value<uint32_t>()->default_value(defaults.knn), "neighbours of the kNN vote")(
      "top", po::value<uint32_t>()->default_value(defaults.top),
      "takes retrieved per take for the precision")(
      "dtw-step", po::value<uint32_t>()->default_value(1),
      "dtw: compare every n-th frame (1: every frame)");
  AddTableFlags(spec, {"weights", "seed"});
  AddWordsReaderOptions(spec, "PREFIX.mwm and PREFIX.mws", "classify");
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
}

// InvalidArgument naming the flag for a bad value; IOError if the output folder cannot be made.
Result<ClassifyCommandOptions> ReadClassifyOptions(const po::variables_map& vm) {
  ClassifyCommandOptions options;
  options.archive = vm["archive"].as<std::string>();
  options.distance_name = vm["distance"].as<std::string>();
  const std::string& distance_name = options.distance_name;
  if (distance_name != "emd" && distance_name != "emd-tf" && distance_name != "dtw" &&
      distance_name != "movement") {
    return Status::InvalidArgument("--distance must be emd, emd-tf, dtw or movement, not '" +
                                   distance_name + "'");
  }
  ClassifyOptions& classify = options.classify;
  const std::string groups = vm["groups"].as<std::string>();
  if (groups != "auto") MOTIF_RETURN_IF_ERROR(ParseGroups(groups, &classify.groups));
  classify.dims = vm["dims"].as<uint32_t>();
  classify.knn = vm["knn"].as<uint32_t>();
  classify.top = vm["top"].as<uint32_t>();
  motifmine::MineOptions table;
  ReadTableFlags(vm, {"weights", "seed", "threads"}, &table);
  classify.seed = table.seed;
  classify.threads = table.threads;
  options.dtw_step = vm["dtw-step"].as<uint32_t>();
  MOTIF_ASSIGN_OR_RETURN(options.output, WordsReaderOutputFrom(vm, options.archive, "classify"));
  options.labels_path = vm["labels"].as<std::string>();
  options.weights_path = table.weights_path;
  options.progress_mode = ProgressModeFrom(vm);
  return options;
}

// The takes to classify: the clips with at least one word, with their labels ("": unlabelled),
// and how many labelled clips are not among them.
struct ClassifiedTakes {
  std::vector<uint32_t> clips;
  std::vector<std::string> names;
  std::vector<std::string> labels;
  uint64_t unknown_labels = 0;
};

ClassifiedTakes SelectClassifiedTakes(const FrameFileReader& reader, const WordOptions& geometry,
                                      const TakeLabels& labels) {
  ClassifiedTakes takes;
  const std::vector<ClipInfo>& clips = reader.clips();
  for (size_t clip = 0; clip < clips.size(); ++clip) {
    if (ClipWordGrid(reader, clip, geometry).word_count() == 0) continue;
    takes.clips.push_back(static_cast<uint32_t>(clip));
    takes.names.push_back(clips[clip].name);
    const auto label = labels.by_clip.find(clips[clip].name);
    takes.labels.push_back(label == labels.by_clip.end() ? "" : label->second);
  }
  for (const auto& [clip, label] : labels.by_clip) {
    takes.unknown_labels +=
        std::find(takes.names.begin(), takes.names.end(), clip) == takes.names.end();
  }
  return takes;
}

// The takes' distance matrix: DTW over their frames, or the EMD between their signatures
// (`words`, null only for dtw). The progress stage opens with the first report of the engine.
Result<Eigen::MatrixXd> ClassifyDistances(const ClassifyCommandOptions& options,
                                          const FrameFileReader& reader, const LoadedWords* words,
                                          const std::vector<uint32_t>& take_clips,
                                          ProgressReporter& progress) {
  bool began = false;
  auto on_progress = [&](uint64_t done, uint64_t total) {
    if (!began) {
      progress.BeginStage(options.needs_words() ? "emd" : options.distance_name, total, "takes");
    }
    began = true;
    progress.Update(done);
  };
  const int threads = options.classify.threads;
  Result<Eigen::MatrixXd> distances = Status::InvalidArgument("no distance");
  if (options.dtw()) {
    MOTIF_ASSIGN_OR_RETURN(std::vector<float> weights,
                           LoadDistanceWeights(reader.skeleton(), options.weights_path));
    MOTIF_ASSIGN_OR_RETURN(PoseFeatures features, PoseFeatures::FromArchive(reader, weights));
    const std::vector<ClipInfo>& clips = reader.clips();
    std::vector<TakeFrames> takes;
    for (uint32_t clip : take_clips) {
      takes.push_back({clips[clip].first_frame, clips[clip].first_frame + clips[clip].frame_count});
    }
    distances = TakeDtwMatrix(features, takes, options.dtw_step, threads, on_progress);
  } else if (options.movement()) {
    distances = TakeMovementMatrix(reader, take_clips, threads, on_progress);
  } else {
    std::vector<std::vector<double>> signatures;
    for (uint32_t clip : take_clips) {
      signatures.push_back(words->ClipSignature(clip, options.distance_name == "emd-tf"));
    }
    distances = SignatureDistanceMatrix(signatures, words->ground, threads, on_progress);
  }
  if (began) progress.EndStage();
  return distances;
}

// What the summary prints besides the classification's own figures.
struct ClassifyOutcome {
  TakeClassification result;
  uint32_t motif_count = 0;  // of the words files; 0 when dtw ran without them
  double seconds_distances = 0;
};

// Reads the archive, the labels and the words files, computes the distances and classifies.
Result<ClassifyOutcome> ClassifyArchiveTakes(const ClassifyCommandOptions& options) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileReader> reader,
                         FrameFileReader::Open(options.archive));
  TakeLabels labels;
  if (!options.labels_path.empty()) {
    MOTIF_ASSIGN_OR_RETURN(labels, ReadTakeLabels(options.labels_path));
  }
  // The takes: clips with at least one word. DTW and movement need no words file: without one,
  // the takes are those long enough for one word of the default geometry, the takes signatures
  // would see.
  const WordsPaths paths = DefaultWordsPaths(options.output.prefix_archive);
  Result<LoadedWords> words = LoadWords(*reader, paths, /*with_embedding=*/false);
  if (!words.ok() && !(!options.needs_words() && words.status().IsNotFound())) {
    return words.status();
  }
  const WordOptions geometry = words.ok() ? words->signatures.words : WordOptions{};
  ClassifiedTakes takes = SelectClassifiedTakes(*reader, geometry, labels);

  ProgressReporter progress(options.progress_mode);
  if (takes.unknown_labels > 0) {
    progress.Note(std::to_string(takes.unknown_labels) + " labelled clips of " +
                  options.labels_path +
                  " are not takes of the archive (absent, or shorter than one word): ignored");
  }
  const auto start = std::chrono::steady_clock::now();
  MOTIF_ASSIGN_OR_RETURN(
      Eigen::MatrixXd distances,
      ClassifyDistances(options, *reader, words.ok() ? &*words : nullptr, takes.clips, progress));
  ClassifyOutcome outcome;
  outcome.seconds_distances =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (words.ok()) outcome.motif_count = words->motifs.motif_count();

  MOTIF_ASSIGN_OR_RETURN(outcome.result,
                         ClassifyTakes(std::move(distances), takes.labels, options.classify));
  outcome.result.distance = options.distance_name;
  outcome.result.names = takes.names;
  outcome.result.clips = takes.clips;
  outcome.result.seconds_distances = outcome.seconds_distances;
  return outcome;
}

Status WriteClassifyFiles(const ClassifyCommandOptions& options, const TakeClassification& result) {
  MOTIF_RETURN_IF_ERROR(AtomicWriteFile(
      options.output.json_path, ClassificationJson(result, options.archive).dump(2) + "\n"));
  return WriteClassificationHtml(options.output.html_path, result, options.archive);
}

// The supervised lines: accuracy, precision and per label how many takes were classified right.
void PrintClassifySupervised(const TakeClassification& r) {
  std::printf(
      "  supervised   %u-NN leave-one-out accuracy %.3f (%s of %s labelled takes, %zu "
      "labels)\n",
      r.knn.k, r.knn.accuracy, WithCommas(r.knn.correct).c_str(),
      WithCommas(r.knn.labelled).c_str(), r.label_names.size());
  std::printf("  retrieval    precision@%u %.3f\n", r.top, r.precision_at_top);
  for (size_t label = 0; label < r.label_names.size(); ++label) {
    uint64_t count = 0;
    for (uint64_t value : r.knn.confusion[label]) count += value;
    std::printf("    %-16s %3llu takes, %llu classified right\n", r.label_names[label].c_str(),
                static_cast<unsigned long long>(count),
                static_cast<unsigned long long>(r.knn.confusion[label][label]));
  }
}

void PrintClassifySummary(const ClassifyCommandOptions& options, const ClassifyOutcome& outcome) {
  const TakeClassification& r = outcome.result;
  std::printf(
      "motifmine classify: %s (%zu takes, distance %s%s)\n", options.archive.c_str(),
      r.names.size(), options.distance_name.c_str(),
      !options.needs_words() ? "" : (" over " + std::to_string(outcome.motif_count) + " motifs").c_str());
  std::printf("  unsupervised MDS into %lld dimensions, k-means into %u groups",
              static_cast<long long>(r.mds.coordinates.cols()), r.group_count);
  if (!r.label_names.empty()) {
    std::printf(": adjusted Rand index %.3f, purity %.3f against the labels", r.adjusted_rand_index,
                r.purity);
  }
  std::printf("\n");
  if (!r.label_names.empty()) PrintClassifySupervised(r);
  std::printf("  time         distances %.2fs\n", outcome.seconds_distances);
  std::printf("  wrote        %s, %s\n", options.output.json_path.c_str(),
              options.output.html_path.c_str());
}

}  // namespace

int RunClassify(const std::vector<std::string>& args) {
  CommandSpec spec;
  AddClassifyOptions(spec);
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const auto fail = [](const Status& status) { return ReportError("classify", status); };
  Result<ClassifyCommandOptions> options = ReadClassifyOptions(vm);
  if (!options.ok()) return fail(options.status());
  Result<ClassifyOutcome> outcome = ClassifyArchiveTakes(*options);
  if (!outcome.ok()) return fail(outcome.status());
  if (Status status = WriteClassifyFiles(*options, outcome->result); !status.ok()) {
    return fail(status);
  }
  PrintClassifySummary(*options, *outcome);
  return kExitOk;
}

}  // namespace motif::cli
