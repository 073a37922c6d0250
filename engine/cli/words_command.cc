// motifmine words ARCHIVE [...]: the motion words of an archive, their embedding (trained, reused,
// resumed or loaded), the motifs and every take's signature (engine/words/words_builder.h).
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "engine/cli/cli_common.h"
#include "engine/cli/table_options.h"
#include "engine/cli/words_on_demand.h"
#include "engine/words/words_builder.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

nlohmann::json WordsReportJson(const std::string& archive, const WordsReport& report) {
  nlohmann::json json;
  json["version"] = 1;
  json["archive"] = archive;
  json["archive_generation"] = report.archive_generation;
  json["files"] = {{"embedding", report.paths.embedding},
                   {"motifs", report.paths.motifs},
                   {"signatures", report.paths.signatures}};
  json["clips"] = report.clips;
  json["takes"] = report.takes;
  json["words"] = report.words;
  json["motifs"] = report.motifs;
  json["dims"] = report.dims;
  json["embedding"] = report.embedding_loaded   ? "loaded"
                      : report.embedding_reused ? "reused"
                                                : "trained";
  json["resumed_from_epoch"] = report.resumed_from_epoch;
  json["motifs_reused"] = report.motifs_reused;
  json["signatures_reused"] = report.signatures_reused;
  json["training"] = {{"pool_words", report.pool_words},
                      {"epoch_loss", report.epoch_loss},
                      {"held_out_triplets", report.accuracy.triplets},
                      {"accuracy_raw", report.accuracy.raw},
                      {"accuracy_untrained", report.accuracy.untrained},
                      {"accuracy_trained", report.accuracy.trained}};
  json["kmeans"] = {{"inertia", report.kmeans_inertia}, {"iterations", report.kmeans_iterations}};
  json["seconds"] = {{"pool", report.seconds_pool},     {"neighbours", report.seconds_neighbours},
                     {"train", report.seconds_train},   {"embed", report.seconds_embed},
                     {"kmeans", report.seconds_kmeans}, {"signatures", report.seconds_signatures}};
  return json;
}

void AddWordsCommandOptions(CommandSpec& spec) {
  spec.name = "words";
  spec.usage =
      "motifmine words ARCHIVE [--motifs K] [--embedding FILE.mwe] [--epochs E] "
      "[--seed S] [--threads T] [options]";
  spec.summary =
      "Cuts ARCHIVE into motion words (16 frames at 24 Hz every 4 frames), trains their\n"
      "embedding with a triplet loss (temporal and DTW neighbours as positives, time-warped\n"
      "copies, far or other-take negatives), embeds every word, clusters them into K motifs\n"
      "(k-means) and writes every take's TF-IDF motion signature, beside the archive:\n"
      "ARCHIVE.mwe (embedding), ARCHIVE.mwm (motifs), ARCHIVE.mws (signatures). Each stage is\n"
      "reused when its inputs did not change; interrupted training resumes from its last epoch.\n"
      "--embedding loads an embedding trained elsewhere instead of training one.";
  WordsOptions defaults;
  spec.options.add_options()("motifs", po::value<uint32_t>()->default_value(defaults.motifs),
                             "number of motifs K")(
      "embedding", po::value<std::string>()->default_value(""),
      "use this trained embedding (.mwe) instead of training one")(
      "prefix", po::value<std::string>()->default_value(""),
      "write PREFIX.mwe, PREFIX.mwm, PREFIX.mws (default: ARCHIVE without .mfs)")(
      "word-frames", po::value<uint32_t>()->default_value(defaults.words.word_frames),
      "frames per word")("stride",
                         po::value<uint32_t>()->default_value(defaults.words.stride_frames),
                         "frames between word starts")(
      "word-fps", NumberWithDefault(defaults.words.word_fps),
      "rate the words are sampled at")(
      "epochs", po::value<uint32_t>()->default_value(defaults.train.epochs), "training epochs")(
      "pool-words", po::value<uint64_t>()->default_value(defaults.pool.max_words),
      "at most this many words are trained on (whole clips, seeded)")(
      "warp-copies", po::value<uint32_t>()->default_value(defaults.pool.warp_copies),
      "time-warped copies per training word")(
      "held-out", NumberWithDefault(defaults.pool.held_out_fraction),
      "fraction of the training clips held out to measure the embedding")(
      "batch", po::value<uint32_t>()->default_value(defaults.train.batch_triplets),
      "triplets per training batch")(
      "learning-rate", NumberWithDefault(defaults.train.learning_rate),
      "Adam's learning rate")("margin", NumberWithDefault(defaults.train.margin),
                              "triplet margin")(
      "dims", po::value<uint32_t>()->default_value(defaults.train.shape.embedding_dims),
      "embedding dimensions")(
      "channels", po::value<uint32_t>()->default_value(defaults.train.shape.conv1_channels),
      "channels of both convolutions")("json", po::value<std::string>()->default_value(""),
                                       "also write this summary as JSON");
  AddTableFlags(spec, {"seed", "threads", "weights"});
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
}

// The command line of `words`, read back (BuildWords checks the values).
struct WordsCommandOptions {
  std::string archive;
  WordsOptions build;
  WordsPaths paths;
  std::string json_path;  // empty: no JSON summary
  ProgressMode progress_mode = ProgressMode::kAuto;
};

WordsCommandOptions ReadWordsCommandOptions(const po::variables_map& vm) {
  WordsCommandOptions command;
  command.archive = vm["archive"].as<std::string>();
  WordsOptions& options = command.build;
  options.motifs = vm["motifs"].as<uint32_t>();
  options.embedding_in = vm["embedding"].as<std::string>();
  motifmine::MineOptions table;
  ReadTableFlags(vm, {"seed", "threads", "weights"}, &table);
  options.seed = table.seed;
  options.threads = table.threads;
  options.weights_path = table.weights_path;
  options.words.word_frames = vm["word-frames"].as<uint32_t>();
  options.words.stride_frames = vm["stride"].as<uint32_t>();
  options.words.word_fps = vm["word-fps"].as<double>();
  options.train.epochs = vm["epochs"].as<uint32_t>();
  options.pool.max_words = vm["pool-words"].as<uint64_t>();
  options.pool.warp_copies = vm["warp-copies"].as<uint32_t>();
  options.pool.held_out_fraction = vm["held-out"].as<double>();
  options.train.batch_triplets = vm["batch"].as<uint32_t>();
  options.train.learning_rate = vm["learning-rate"].as<double>();
  options.train.margin = vm["margin"].as<double>();
  options.train.shape.embedding_dims = vm["dims"].as<uint32_t>();
  options.train.shape.conv1_channels = vm["channels"].as<uint32_t>();
  options.train.shape.conv2_channels = vm["channels"].as<uint32_t>();
  const std::string prefix = vm["prefix"].as<std::string>();
  command.paths = DefaultWordsPaths(prefix.empty() ? command.archive : prefix + ".mfs");
  command.json_path = vm["json"].as<std::string>();
  command.progress_mode = ProgressModeFrom(vm);
  return command;
}

// The embedding line: loaded, or trained / reused (resumed) with its epochs' losses.
void PrintWordsEmbedding(const WordsOptions& options, const WordsReport& r) {
  if (r.embedding_loaded) {
    std::printf("  embedding    loaded from %s (%u dimensions)\n", options.embedding_in.c_str(),
                r.dims);
    return;
  }
  std::printf("  embedding    %s%s: %u dimensions, %s training words, %zu epochs",
              r.embedding_reused ? "reused" : "trained",
              r.resumed_from_epoch
                  ? (" (resumed after epoch " + std::to_string(r.resumed_from_epoch) + ")").c_str()
                  : "",
              r.dims, WithCommas(r.pool_words).c_str(), r.epoch_loss.size());
  if (!r.epoch_loss.empty()) {
    std::printf(", loss %.4f -> %.4f", r.epoch_loss.front(), r.epoch_loss.back());
  }
  std::printf("\n");
}

void PrintWordsSummary(const WordsCommandOptions& command, const WordsReport& r) {
  std::printf("motifmine words: %s\n", command.archive.c_str());
  std::printf("  words        %s in %s takes (%s clips)\n", WithCommas(r.words).c_str(),
              WithCommas(r.takes).c_str(), WithCommas(r.clips).c_str());
  PrintWordsEmbedding(command.build, r);
  if (r.accuracy.triplets > 0) {
    std::printf(
        "  held out     triplet accuracy %.3f trained, %.3f untrained, %.3f raw "
        "features (%s triplets)\n",
        r.accuracy.trained, r.accuracy.untrained, r.accuracy.raw,
        WithCommas(r.accuracy.triplets).c_str());
  }
  std::printf("  motifs       %u%s (k-means inertia %.4g, %u iterations)\n", r.motifs,
              r.motifs_reused ? ", reused" : "", r.kmeans_inertia, r.kmeans_iterations);
  std::printf("  signatures   %s takes%s\n", WithCommas(r.takes).c_str(),
              r.signatures_reused ? ", reused" : "");
  std::printf(
      "  time         pool %.1fs, neighbours %.1fs, train %.1fs, embed %.1fs, k-means "
      "%.1fs, signatures %.1fs\n",
      r.seconds_pool, r.seconds_neighbours, r.seconds_train, r.seconds_embed, r.seconds_kmeans,
      r.seconds_signatures);
  std::printf("  memory       peak resident %s\n", FormatBytes(PeakResidentBytes()).c_str());
  std::printf("  wrote        %s, %s, %s\n", r.paths.embedding.c_str(), r.paths.motifs.c_str(),
              r.paths.signatures.c_str());
}

}  // namespace

int RunWords(const std::vector<std::string>& args) {
  CommandSpec spec;
  AddWordsCommandOptions(spec);
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  WordsCommandOptions command = ReadWordsCommandOptions(vm);

  ProgressReporter progress(command.progress_mode);
  ReportWordsProgress(progress, &command.build);
  Result<WordsReport> report = BuildWords(command.archive, command.paths, command.build);
  progress.EndStages();
  if (!report.ok()) return ReportError("words", report.status());

  PrintWordsSummary(command, *report);
  if (!command.json_path.empty()) {
    nlohmann::json json = WordsReportJson(command.archive, *report);
    json["peak_resident_bytes"] = PeakResidentBytes();
    if (Status status = AtomicWriteFile(command.json_path, json.dump(2) + "\n"); !status.ok()) {
      return ReportError("words", status);
    }
  }
  return kExitOk;
}

}  // namespace motif::cli
