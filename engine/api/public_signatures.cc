// The signature calls of the public API (include/motifmine/signatures.h) over the engine's
// BuildWords, LoadWords and SlidingWindowSearch.
#include <memory>

#include "engine/api/public_status.h"
#include "engine/words/range_query.h"
#include "engine/words/window_search.h"
#include "engine/words/word_model.h"
#include "engine/words/words_builder.h"
#include "formats/frame_file/frame_file_reader.h"
#include "motifmine/signatures.h"

namespace motifmine {

WordsOptions::WordsOptions() {
  const motif::WordsOptions defaults;
  motifs = defaults.motifs;
  seed = defaults.seed;
  threads = defaults.threads;
}

Status BuildWords(const std::string& archive_path, const WordsOptions& options,
                  WordsResult* result) {
  if (result == nullptr) return {Status::Code::kInvalidArgument, "no WordsResult to fill"};
  motif::WordsOptions words;
  words.motifs = options.motifs;
  words.seed = options.seed;
  words.threads = options.threads;
  if (options.progress) {
    words.progress = [progress = options.progress](const std::string& stage, uint64_t done,
                                                   uint64_t total, const std::string&) {
      progress(stage, done, total);
    };
  }
  const motif::WordsPaths paths = motif::DefaultWordsPaths(archive_path);
  motif::Result<motif::WordsReport> report = motif::BuildWords(archive_path, paths, words);
  if (!report.ok()) return motif::ToPublicStatus(report.status());
  *result = {report->takes,   report->words, report->motifs,
             paths.embedding, paths.motifs,  paths.signatures};
  return {};
}

namespace {

struct OpenedWords {
  std::unique_ptr<motif::FrameFileReader> reader;
  motif::LoadedWords words;
};

motif::Result<OpenedWords> OpenWords(const std::string& archive_path) {
  OpenedWords opened;
  MOTIF_ASSIGN_OR_RETURN(opened.reader, motif::FrameFileReader::Open(archive_path));
  MOTIF_ASSIGN_OR_RETURN(opened.words,
                         motif::LoadWords(*opened.reader, motif::DefaultWordsPaths(archive_path),
                                          /*with_embedding=*/false));
  return opened;
}

}  // namespace

Status LoadSignatures(const std::string& archive_path, Signatures* signatures) {
  if (signatures == nullptr) return {Status::Code::kInvalidArgument, "no Signatures to fill"};
  motif::Result<OpenedWords> opened = OpenWords(archive_path);
  if (!opened.ok()) return motif::ToPublicStatus(opened.status());
  *signatures = Signatures();
  for (const motif::ClipInfo& clip : opened->reader->clips())
    signatures->clips.push_back(clip.name);
  signatures->motifs = opened->words.signatures.motif_count;
  signatures->values = opened->words.signatures.signatures;
  return {};
}

Status SearchClipRange(const std::string& archive_path, const std::string& clip, uint64_t start,
                       uint64_t end, uint32_t top, std::vector<SearchMatch>* matches) {
  if (matches == nullptr) return {Status::Code::kInvalidArgument, "no match list to fill"};
  motif::Result<OpenedWords> opened = OpenWords(archive_path);
  if (!opened.ok()) return motif::ToPublicStatus(opened.status());
  const motif::FrameFileReader& reader = *opened->reader;
  uint32_t index = UINT32_MAX;
  for (uint32_t i = 0; i < reader.clips().size(); ++i) {
    if (reader.clips()[i].name == clip) index = i;
  }
  if (index == UINT32_MAX) {
    return {Status::Code::kNotFound, archive_path + ": no clip named '" + clip + "'"};
  }
  if (start >= end || end > reader.clips()[index].frame_count) {
    return {Status::Code::kInvalidArgument, "start and end: frames [" + std::to_string(start) +
                                                ", " + std::to_string(end) +
                                                ") are not a range within clip '" + clip + "'"};
  }
  motif::Result<motif::RangeQuery> words =
      motif::RangeQueryWords(reader, opened->words, index, start, end);
  if (!words.ok()) return motif::ToPublicStatus(words.status());
  const motif::WindowQuery query = motif::ToWindowQuery(*words, opened->words);
  motif::Result<motif::SearchResult> found =
      motif::SlidingWindowSearch(reader, opened->words, query, top, /*threads=*/0);
  if (!found.ok()) return motif::ToPublicStatus(found.status());
  matches->clear();
  for (const motif::WindowMatch& match : found->matches) {
    matches->push_back(
        {reader.clips()[match.clip].name, match.start_frame, match.end_frame, match.distance});
  }
  return {};
}

}  // namespace motifmine
