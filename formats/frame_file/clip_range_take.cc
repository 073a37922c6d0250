#include "formats/frame_file/clip_range_take.h"

#include <string>
#include <vector>

#include "formats/motion/pose_frames.h"

namespace motif {

Take SliceTake(const Take& take, size_t start, size_t end) {
  Take slice = take;
  const size_t joint_count = take.joint_count();
  slice.root_positions.assign(take.root_positions.begin() + start,
                              take.root_positions.begin() + end);
  slice.rotations.assign(take.rotations.begin() + start * joint_count,
                         take.rotations.begin() + end * joint_count);
  return slice;
}

Result<Take> ReadClipRangeAsTake(const FrameFileReader& reader, const ClipInfo& clip,
                                 uint64_t start, uint64_t end) {
  if (start >= end || end > clip.frame_count) {
    return Status::InvalidArgument("frame range [" + std::to_string(start) + ", " +
                                   std::to_string(end) + ") is not inside clip '" + clip.name +
                                   "', which has " + std::to_string(clip.frame_count) + " frames");
  }
  std::vector<float> rows;
  MOTIF_RETURN_IF_ERROR(reader.ReadFrames(clip.first_frame, end, &rows));
  const Take take = ClipFramesToTake(reader.skeleton(), clip, rows.data(), end);
  return SliceTake(take, start, end);
}

}  // namespace motif
