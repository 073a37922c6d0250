// Playback data of motif instances for report.html's player: every frame of an instance,
// sampled down to at most kPlaybackFps, as the 3D points of its stick figure (forward kinematics
// of the archive's frames, heading kept), quantised to int16 and base64-encoded, so that the page
// can play, turn and scrub any instance without the archive.
//
// Encoding of one instance (the player: docs/guide.md, "The report and motif export", item 4):
// samples k = 0 .. samples-1 are clip frames start + k * step; each sample holds the layout's
// points (StickFigureLayout::points, in that order), each x, y, z as little-endian int16; a world
// coordinate is value / scale + origin (origin: the root's ground position at the first sample, x
// and z, and the lowest point of the instance, y). The figure is the same for every instance: the
// layout's chains, each point's side (0 centre, 1 left, 2 right, from the joint names) and the rest
// pose's height.
// Thread-safety: one InstancePlayback per thread (it caches frames read from the archive).
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/report/frame_chunk_cache.h"
#include "engine/report/limb_side.h"  // JointSide: the sides of FigureJson
#include "engine/report/stick_figure_svg.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

inline constexpr double kPlaybackFps = 30.0;

// Archive frames per playback sample at `fps`: round(fps / kPlaybackFps), at least 1.
uint32_t PlaybackStep(double fps);

struct PlaybackInstance {
  uint64_t start = 0;  // clip frames [start, end)
  uint64_t end = 0;
  uint32_t samples = 0;
  double scale = 1;                // int16 units per skeleton unit
  std::array<double, 3> origin{};  // added to every decoded point
  double heading_rad = 0;          // the root's heading at the first sample
  std::string points_base64;       // samples * points * 3 int16, little-endian
  std::vector<float> sample_rows;  // the samples' archive rows (samples * stride floats)
};

class InstancePlayback {
 public:
  // `reader` and `layout` must outlive this object.
  InstancePlayback(const FrameFileReader& reader, const StickFigureLayout& layout);

  // Archive frames per sample: round(fps / kPlaybackFps), at least 1.
  uint32_t step() const { return step_; }
  size_t stride() const { return reader_.layout().stride(); }

  // The samples of clip frames [start, end) (start < end <= clip.frame_count). Errors of the
  // reader pass through. Frames are read in chunks of at least 4,096 and kept: encode the
  // instances in archive order, and a block is decoded about once.
  Result<PlaybackInstance> Encode(const ClipInfo& clip, uint64_t start, uint64_t end);

  // {"step":S,"fps":F,"height":H,"root":R,"sides":[...],"colours":[...],"chains":[[...],...]}:
  // what the page needs to draw any instance (R and the chains index the layout's points; a
  // bone's colour is colours[sides[its child point]], LimbSideColoursJson).
  std::string FigureJson() const;

 private:
  const FrameFileReader& reader_;
  const StickFigureLayout& layout_;
  FrameChunkCache cache_;
  uint32_t step_ = 1;
  double height_ = 1;
};

std::string Base64(const uint8_t* bytes, size_t size);

}  // namespace motif
