// The pages of `motifmine search` and `motifmine classify`, in the style of the motif report
// (html_page.h; one self-contained file that opens from disk):
//  * search: the query (with keyframe figures when it comes from the archive), then the matches
//    best first, each with its clip, frames, EMD, keyframe figures of the matched window and a
//    strip of the EMD of every window along its take (darker: closer, the paper's figure 9);
//  * classify: the scores (adjusted Rand index and purity of the unsupervised groups, kNN
//    accuracy, retrieval precision), the MDS map of the takes (first two coordinates) coloured
//    by group and by label, the confusion matrix, the distance matrix ordered by label, and
//    every take with its group, prediction and nearest takes.
// Thread-safety: pure functions (the reader's const methods are thread-safe).
#pragma once

#include <string>
#include <vector>

#include "common/status.h"
#include "engine/words/take_classification.h"
#include "engine/words/window_search.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/motion/take.h"

namespace motif {

struct SearchPageInfo {
  std::string archive;
  std::string query_text;  // "clip 05_03 frames 100-400", "file move.bvh"
  bool query_in_archive = false;
  uint32_t query_clip = 0;  // when query_in_archive: the clip and frames drawn
  uint64_t query_start = 0;
  uint64_t query_end = 0;
  const Take* query_take = nullptr;  // a file query fitted to the archive (drawn), or null
  uint64_t query_words = 0;
  std::vector<std::string> notes;  // what was done to the query (padded, its windows left out)
  uint32_t motifs = 0;
  double seconds = 0;
};

Result<std::string> SearchHtmlText(const SearchResult& result, const FrameFileReader& reader,
                                   const SearchPageInfo& info);
// Writes it atomically. Errors of the reader, IOError / ResourceExhausted.
Status WriteSearchHtml(const std::string& path, const SearchResult& result,
                       const FrameFileReader& reader, const SearchPageInfo& info);

std::string ClassificationHtmlText(const TakeClassification& result, const std::string& archive);
Status WriteClassificationHtml(const std::string& path, const TakeClassification& result,
                               const std::string& archive);

}  // namespace motif
