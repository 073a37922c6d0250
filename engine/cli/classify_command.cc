// motifmine classify ARCHIVE [--labels FILE.tsv] [...]: the takes of an archive classified by
// their motion signatures (unsupervised: MDS and k-means; supervised: leave-one-out kNN with the
// labels, and whole-take retrieval precision), or by a baseline distance.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "common/file_util.h"
#include "engine/cli/cli_common.h"
#include "engine/cli/take_labels.h"
#include "engine/distance/pose_features.h"
#include "engine/report/words_report_html.h"
#include "engine/signature/signature_matrix.h"
#include "engine/signature/take_dtw.h"
#include "engine/signature/word_stream.h"
#include "engine/words/take_classification.h"
#include "engine/words/word_model.h"

namespace motif::cli {

namespace po = boost::program_options;

int RunClassify(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "classify";
  spec.usage =
      "motifmine classify ARCHIVE [--labels FILE.tsv] [--distance emd|emd-tf|dtw] "
      "[--groups G] [--knn K] [--top T] [--out DIR]";
  spec.summary =
      "Classifies the takes of ARCHIVE (those with at least one motion word) by the Earth\n"
      "Mover's Distance between their motion signatures (run `motifmine words` first).\n"
      "Unsupervised: classical MDS of the distance matrix, then k-means into G groups.\n"
      "Supervised (--labels, a TSV of clip and label): leave-one-out k-nearest-neighbour\n"
      "accuracy, and whole-take retrieval precision at T. --distance emd-tf compares the\n"
      "signatures without TF-IDF, dtw the takes' frames by dynamic time warping (baselines).\n"
      "Writes DIR/classify.json and DIR/classify.html.";
  ClassifyOptions defaults;
  spec.options.add_options()("labels", po::value<std::string>()->default_value(""),
                             "labels of takes: a TSV file of clip<TAB>label lines")(
      "distance", po::value<std::string>()->default_value("emd"),
      "emd (TF-IDF signatures), emd-tf (term frequencies only) or dtw (frames)")(
      "groups", po::value<std::string>()->default_value("auto"),
      "unsupervised groups, or auto (the number of labels, else 8)")(
      "dims", po::value<uint32_t>()->default_value(defaults.dims), "MDS dimensions")(
      "knn", po::value<uint32_t>()->default_value(defaults.knn), "neighbours of the kNN vote")(
      "top", po::value<uint32_t>()->default_value(defaults.top),
      "takes retrieved per take for the precision")(
      "dtw-step", po::value<uint32_t>()->default_value(1),
      "dtw: compare every n-th frame (1: every frame)")(
      "weights", po::value<std::string>()->default_value(""),
      "dtw: per-joint weights file (default: the skeleton's)")(
      "seed", po::value<uint64_t>()->default_value(defaults.seed), "seed of k-means");
  AddWordsReaderOptions(spec, "PREFIX.mwm and PREFIX.mws", "classify");
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const auto fail = [](const Status& status) { return ReportError("classify", status); };
  const std::string archive = vm["archive"].as<std::string>();
  const std::string distance_name = vm["distance"].as<std::string>();
  if (distance_name != "emd" && distance_name != "emd-tf" && distance_name != "dtw") {
    return fail(Status::InvalidArgument("--distance must be emd, emd-tf or dtw, not '" +
                                        distance_name + "'"));
  }
  ClassifyOptions options;
  const std::string groups = vm["groups"].as<std::string>();
  if (groups != "auto") {
    if (Status status = ParseGroups(groups, &options.groups); !status.ok()) return fail(status);
  }
  options.dims = vm["dims"].as<uint32_t>();
  options.knn = vm["knn"].as<uint32_t>();
  options.top = vm["top"].as<uint32_t>();
  options.seed = vm["seed"].as<uint64_t>();
  options.threads = vm["threads"].as<int>();
  const uint32_t dtw_step = vm["dtw-step"].as<uint32_t>();
  if (options.dims == 0 || options.knn == 0 || options.top == 0 || dtw_step == 0) {
    return fail(Status::InvalidArgument("--dims, --knn, --top and --dtw-step must be at least 1"));
  }
  Result<WordsReaderOutput> output = WordsReaderOutputFrom(vm, archive, "classify");
  if (!output.ok()) return fail(output.status());
  const WordsPaths paths = DefaultWordsPaths(output->prefix_archive);

  Result<std::unique_ptr<FrameFileReader>> reader = FrameFileReader::Open(archive);
  if (!reader.ok()) return fail(reader.status());
  TakeLabels labels;
  const std::string labels_path = vm["labels"].as<std::string>();
  if (!labels_path.empty()) {
    Result<TakeLabels> read = ReadTakeLabels(labels_path);
    if (!read.ok()) return fail(read.status());
    labels = std::move(read.value());
  }
  // The takes: clips with at least one word. DTW needs no words file: without one, the takes are
  // those long enough for one word of the default geometry, the takes signatures would see.
  Result<LoadedWords> words = LoadWords(**reader, paths, /*with_embedding=*/false);
  const bool dtw = distance_name == "dtw";
  if (!words.ok() && !(dtw && words.status().IsNotFound())) return fail(words.status());
  const WordOptions geometry = words.ok() ? words->signatures.words : WordOptions{};
  TakeClassification named;
  std::vector<std::string> take_labels;
  const std::vector<ClipInfo>& clips = (*reader)->clips();
  for (size_t clip = 0; clip < clips.size(); ++clip) {
    if (ClipWordGrid(**reader, clip, geometry).word_count() == 0) continue;
    named.clips.push_back(static_cast<uint32_t>(clip));
    named.names.push_back(clips[clip].name);
    const auto label = labels.by_clip.find(clips[clip].name);
    take_labels.push_back(label == labels.by_clip.end() ? "" : label->second);
  }
  uint64_t unknown = 0;
  for (const auto& [clip, label] : labels.by_clip) {
    unknown += std::find(named.names.begin(), named.names.end(), clip) == named.names.end();
  }

  ProgressReporter progress(ProgressModeFrom(vm));
  bool began = false;
  auto on_progress = [&](uint64_t done, uint64_t total) {
    if (!began) progress.BeginStage(distance_name == "dtw" ? "dtw" : "emd", total, "takes");
    began = true;
    progress.Update(done);
  };
  if (unknown > 0) {
    progress.Note(std::to_string(unknown) + " labelled clips of " + labels_path +
                  " are not takes of the archive (absent, or shorter than one word): ignored");
  }
  const auto start = std::chrono::steady_clock::now();
  Result<Eigen::MatrixXd> distances = Status::InvalidArgument("no distance");
  if (distance_name == "dtw") {
    Result<std::vector<float>> weights =
        LoadDistanceWeights((*reader)->skeleton(), vm["weights"].as<std::string>());
    if (!weights.ok()) return fail(weights.status());
    Result<PoseFeatures> features = PoseFeatures::FromArchive(**reader, *weights);
    if (!features.ok()) return fail(features.status());
    std::vector<TakeFrames> takes;
    for (uint32_t clip : named.clips) {
      takes.push_back({clips[clip].first_frame, clips[clip].first_frame + clips[clip].frame_count});
    }
    distances = TakeDtwMatrix(*features, takes, dtw_step, options.threads, on_progress);
  } else {
    std::vector<std::vector<double>> signatures;
    for (uint32_t clip : named.clips) {
      signatures.push_back(words->ClipSignature(clip, distance_name == "emd-tf"));
    }
    distances = SignatureDistanceMatrix(signatures, words->ground, options.threads, on_progress);
  }
  if (began) progress.EndStage();
  if (!distances.ok()) return fail(distances.status());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  Result<TakeClassification> result = ClassifyTakes(std::move(*distances), take_labels, options);
  if (!result.ok()) return fail(result.status());
  result->distance = distance_name;
  result->names = named.names;
  result->clips = named.clips;
  result->seconds_distances = seconds;

  const std::string& json_path = output->json_path;
  const std::string& html_path = output->html_path;
  if (Status status =
          AtomicWriteFile(json_path, ClassificationJson(*result, archive).dump(2) + "\n");
      !status.ok()) {
    return fail(status);
  }
  if (Status status = WriteClassificationHtml(html_path, *result, archive); !status.ok()) {
    return fail(status);
  }

  const TakeClassification& r = *result;
  std::printf(
      "motifmine classify: %s (%zu takes, distance %s%s)\n", archive.c_str(), r.names.size(),
      distance_name.c_str(),
      dtw ? "" : (" over " + std::to_string(words->motifs.motif_count()) + " motifs").c_str());
  std::printf("  unsupervised MDS into %lld dimensions, k-means into %u groups",
              static_cast<long long>(r.mds.coordinates.cols()), r.group_count);
  if (!r.label_names.empty()) {
    std::printf(": adjusted Rand index %.3f, purity %.3f against the labels", r.adjusted_rand_index,
                r.purity);
  }
  std::printf("\n");
  if (!r.label_names.empty()) {
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
  std::printf("  time         distances %.2fs\n", seconds);
  std::printf("  wrote        %s, %s\n", json_path.c_str(), html_path.c_str());
  return kExitOk;
}

}  // namespace motif::cli
