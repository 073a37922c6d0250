// The page of `motifmine segment` (DIR/segments.html), in the style of the motif report
// (html_page.h; one self-contained file that opens from disk): how the takes were segmented,
// a legend of the labels, and per take a timeline coloured by label (one box per segment, its
// width in proportion to its frames, hover for its label and frames), then each segment's
// label, frames and a strip of stick-figure keyframes (keyframe_figures.h). With many segments
// only the first kMaxSegmentFigures get figures (the page says so); every timeline is drawn.
// Thread-safety: pure functions (the reader's const methods are thread-safe).
#pragma once

#include <cstdint>
#include <string>

#include "common/status.h"
#include "engine/words/take_segmentation.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

inline constexpr uint64_t kMaxSegmentFigures = 300;

struct SegmentsPageInfo {
  std::string archive;
  std::string labels_path;  // supervised: the labels file
  uint32_t motifs = 0;
  double seconds = 0;
};

// Errors of the reader pass through.
Result<std::string> SegmentsHtmlText(const Segmentation& result, const FrameFileReader& reader,
                                     const SegmentsPageInfo& info);
// Writes it atomically. Errors of the reader, IOError / ResourceExhausted.
Status WriteSegmentsHtml(const std::string& path, const Segmentation& result,
                         const FrameFileReader& reader, const SegmentsPageInfo& info);

}  // namespace motif
