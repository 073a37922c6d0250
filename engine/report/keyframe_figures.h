// KeyframeFigures: stick figures of evenly spaced keyframes of a clip's frame range, read from
// the archive (a chunk of frames at a time, cached, so ranges visited in archive order decode
// each block about once) and projected for a page (stick_figure_svg.h). Each figure is centred
// on its own root; the range's first keyframe's heading is removed from all of them, so ranges
// line up and a turn within one still shows. Used by the motif report and the search page.
// Thread-safety: one thread at a time (the cache).
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "engine/report/frame_chunk_cache.h"
#include "engine/report/stick_figure_svg.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

class KeyframeFigures {
 public:
  // `reader` must outlive this object.
  KeyframeFigures(const FrameFileReader& reader, FigureView view, uint32_t keyframes);

  const StickFigureLayout& layout() const { return layout_; }
  const FigureProjection& projection() const { return projection_; }

  // The keyframes of frames [start, end) of `clip` (clip-relative, start < end <=
  // clip.frame_count): the first and last frames and evenly spaced ones between, projected.
  // Errors of the reader pass through.
  Result<std::vector<std::vector<FigurePoint>>> Project(const ClipInfo& clip, uint64_t start,
                                                        uint64_t end);
  // The clip frames Project draws for [start, end): the first and last and evenly spaced ones.
  std::vector<uint64_t> KeyframeFrames(uint64_t start, uint64_t end) const;
  // The figures of clip frames `frames` of `clip` (non-empty, ascending, each < clip.frame_count),
  // drawn as Project draws its keyframes. Errors of the reader pass through.
  Result<std::vector<std::vector<FigurePoint>>> ProjectFrames(const ClipInfo& clip,
                                                              const std::vector<uint64_t>& frames);
  // The archive rows of clip frames start, start + step, ... below end (start < end <=
  // clip.frame_count), stride floats each: what instance_alignment.h aligns. Through the same
  // cache as the figures, so reading an instance for both decodes its blocks once.
  Result<std::vector<float>> SampleRows(const ClipInfo& clip, uint64_t start, uint64_t end,
                                        uint32_t step);
  // The keyframes of a whole take in the archive's skeleton (a query file fitted to it), as SVG
  // strings side by side, drawn as an instance's are.
  std::string TakeSvg(const Take& take) const;
  // The same, as SVG strings side by side.
  Result<std::string> Svg(const ClipInfo& clip, uint64_t start, uint64_t end);

 private:
  // The figures of frames `frames` of `take`, each centred on its root, all over the lowest
  // point among them, the heading of the first removed.
  std::vector<std::vector<FigurePoint>> ProjectTakeFrames(const Take& take,
                                                          const std::vector<size_t>& frames) const;

  const FrameFileReader& reader_;
  uint32_t keyframes_ = 5;
  StickFigureLayout layout_;
  FigureProjection projection_;
  size_t stride_ = 0;
  FrameChunkCache cache_;
};

}  // namespace motif
