#include "engine/cli/words_on_demand.h"

namespace motif::cli {
namespace {

Status BuildMissingWords(const std::string& archive, const WordsPaths& paths, uint64_t seed,
                         int threads, ProgressReporter& progress) {
  progress.Note("no motion words for " + archive + " yet: building them (motifmine words)");
  WordsOptions options;
  options.seed = seed;
  options.threads = threads;
  ReportWordsProgress(progress, &options);
  Result<WordsReport> report = BuildWords(archive, paths, options);
  progress.EndStages();
  return report.status();
}

}  // namespace

void ReportWordsProgress(ProgressReporter& progress, WordsOptions* options) {
  options->progress = [&progress](const std::string& stage, uint64_t done, uint64_t total,
                                  const std::string& unit) {
    progress.StageUpdate(stage, done, total, unit);
  };
  options->note = [&progress](const std::string& message) { progress.Note(message); };
}

Result<LoadedWords> LoadOrBuildWords(const std::string& archive, const FrameFileReader& reader,
                                     const WordsPaths& paths, uint64_t seed, int threads,
                                     ProgressReporter& progress) {
  Result<LoadedWords> words = LoadWords(reader, paths, /*with_embedding=*/false);
  if (words.ok() || !words.status().IsNotFound()) return words;
  MOTIF_RETURN_IF_ERROR(BuildMissingWords(archive, paths, seed, threads, progress));
  return LoadWords(reader, paths, /*with_embedding=*/false);
}

Result<LoadedWords> LoadWordsOrGrid(const std::string& archive, const FrameFileReader& reader,
                                    const WordsPaths& paths, ProgressReporter& progress) {
  Result<LoadedWords> words = LoadWords(reader, paths, /*with_embedding=*/false);
  if (words.ok() || !words.status().IsNotFound()) return words;
  progress.Note("no motion words for " + archive +
                ": cutting them with the default geometry (no embedding is needed)");
  return WordGridOnly(reader, WordOptions{});
}

}  // namespace motif::cli
