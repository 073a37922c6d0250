// The visual report of a mining run: one self-contained HTML file (inline CSS, a small inline
// script, no network access; it opens from disk in any browser) that shows
//  * an overview: the archive, the parameters, per-stage timings, peak memory, how many motifs
//    and instances were found and how much of the archive they cover, and, for a synthetic
//    archive, the score against the planted motifs;
//  * a timeline per clip that holds instances: a bar with every instance as a rectangle coloured
//    by its motif (hover: "motif N, frames a–b"; click: jump to the motif);
//  * every motif, most important first: its length, instance count and clips, and for up to
//    `instances_per_motif` instances a strip of stick-figure keyframes (stick_figure_svg.h),
//    figure k of each strip the same moment of the movement (aligned_keyframes.h).
// Scaling: the first `eager_motifs` motifs' figures are written as SVG; the others as compact
// projected points (EncodeFigurePoints) in one JSON block, drawn by the script when a motif
// scrolls into view, so 1,000 motifs stay a few megabytes.
// Reads the drawn instances' frames from the archive (to align them and draw their keyframes), in
// archive order, a chunk at a time.
// Thread-safety: pure functions (the reader's const methods are thread-safe).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/cluster/motifs_json.h"
#include "engine/evaluation/planted_motif_score.h"
#include "engine/report/html_page.h"
#include "engine/report/stick_figure_svg.h"
#include "formats/frame_file/frame_file_reader.h"
#include "motifmine/defaults.h"

namespace motif {

struct ReportStageTiming {
  std::string stage;  // "trellis", "grow", ...
  double seconds = 0;
};

// Overview data the motifs document does not hold. Everything is optional.
struct ReportInfo {
  std::string archive_path;                // shown; empty: the document's "archive"
  std::string parameters_text;             // free text shown under the parameters (a command
                                           // line, extra options), escaped
  std::vector<ReportStageTiming> timings;  // in pipeline order
  uint64_t peak_memory_bytes = 0;          // 0: not recorded
  std::optional<PlantedMotifScore> planted_score;  // against a synthetic archive's truth
  std::string truth_path;                          // where the planted motifs came from
  // Descriptions given to this run by clip name, shown over those the archive stored at import
  // (a rerun's --descriptions reaches takes imported before it).
  std::map<std::string, std::string> descriptions;
};

struct ReportOptions {
  FigureView view = FigureView::kSide;
  uint32_t keyframes = 5;  // figures per instance, at aligned moments (aligned_keyframes.h)
  uint32_t instances_per_motif = 4;    // instances drawn per motif (other clips preferred)
  uint32_t eager_motifs = 50;          // motifs drawn as SVG in the file; the rest by the script
  uint32_t clip_names_per_motif = 12;  // clip names listed per motif before "+N more"
  // Playback data embedded for the player (instance_playback.h), motif by motif in rank order,
  // up to this many bytes; the later motifs say how to raise it.
  uint64_t playback_bytes = uint64_t{motifmine::defaults::kPlaybackMegabytes} << 20;
};

// The report's HTML. InvalidArgument if the document does not match the archive
// (CheckMotifsMatchArchive); Corruption if a frame does not decode.
Result<std::string> ReportHtmlText(const MotifsDocument& document, const FrameFileReader& reader,
                                   const ReportInfo& info, const ReportOptions& options = {});

// Writes ReportHtmlText(...) to `path` atomically. As above, plus IOError / ResourceExhausted.
Status WriteReportHtml(const std::string& path, const MotifsDocument& document,
                       const FrameFileReader& reader, const ReportInfo& info,
                       const ReportOptions& options = {});

}  // namespace motif
