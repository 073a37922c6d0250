// The words files a command needs (segment, graph), read back, or built first as
// `motifmine words` with its defaults would build them when they are missing (with a note on
// the progress output, and its stages shown as progress).
#pragma once

#include <cstdint>
#include <string>

#include "common/status.h"
#include "engine/cli/progress_reporter.h"
#include "engine/words/word_model.h"
#include "engine/words/words_builder.h"

namespace motif::cli {

// Shows BuildWords's stages and notes on `progress` (options->progress and options->note).
void ReportWordsProgress(ProgressReporter& progress, WordsOptions* options);

// Errors of LoadWords other than NotFound, and of BuildWords, pass through.
Result<LoadedWords> LoadOrBuildWords(const std::string& archive, const FrameFileReader& reader,
                                     const WordsPaths& paths, uint64_t seed, int threads,
                                     ProgressReporter& progress);

// The words files when they exist (errors of LoadWords other than NotFound pass through), else
// only the words' places with the default geometry (WordGridOnly), with a note on `progress`.
Result<LoadedWords> LoadWordsOrGrid(const std::string& archive, const FrameFileReader& reader,
                                    const WordsPaths& paths, ProgressReporter& progress);

}  // namespace motif::cli
