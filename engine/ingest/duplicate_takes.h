// DuplicateTakes: finds a take whose frames are those of a clip already in the archive, or of one
// added earlier in the same import: the same capture stored as BVH and as ASF/AMC has other
// bytes (so another content hash) but the same joint rotations, and mined together the pair
// comes back as a motif of two identical instances. Two clips are copies when they have the same
// number of frames and, at 16 evenly spaced frames, every joint's rotation agrees within
// kCopyTolerance (a quaternion component; q and -q are one rotation). The root's height and
// velocity are left out: formats store them in other units. Stored clips are read only when one
// has the new take's frame count.
// Thread-safety: one thread (the import's serial stage).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "formats/frame_file/frame_file_reader.h"
#include "formats/motion/pose_frames.h"

namespace motif {

class DuplicateTakes {
 public:
  // About 1 degree of rotation: far above the archive's quantisation (3e-5 between the BVH and
  // the AMC of CMU 05_02), far below two takes of one movement.
  static constexpr float kCopyTolerance = 0.01f;
  static constexpr uint32_t kSamples = 16;

  // `stored`: the archive as it was before this import (null: none).
  DuplicateTakes(const FrameFileReader* stored, FrameLayout layout);

  // The clip `clip` copies, or nothing. Reader errors pass through.
  Result<std::optional<ClipInfo>> FindCopy(const ClipFrames& clip);
  // A clip appended by this import.
  void Add(const ClipFrames& clip);

 private:
  struct Known {
    ClipInfo info;
    std::vector<float> samples;  // empty: not read yet (a stored clip)
  };
  std::vector<float> Samples(const float* rows, uint64_t frame_count) const;
  Status ReadSamples(Known* known) const;
  bool Same(const std::vector<float>& a, const std::vector<float>& b) const;

  const FrameFileReader* stored_;
  FrameLayout layout_;
  std::multimap<uint64_t, Known> by_frames_;  // frame count -> clips
};

}  // namespace motif
