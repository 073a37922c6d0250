#include "formats/motion/resample.h"

#include <cmath>

namespace motif {

bool SameFrameRate(double a_fps, double b_fps) {
  return std::abs(a_fps - b_fps) <= 1e-3 * std::max(a_fps, b_fps);
}

Take ResampleTake(const Take& take, double target_fps) {
  Take out = take;
  if (SameFrameRate(take.fps, target_fps) || take.frame_count() == 0) {
    out.fps = target_fps;
    return out;
  }
  const size_t source_frames = take.frame_count();
  const size_t joint_count = take.joint_count();
  const double ratio = take.fps / target_fps;  // source frames per output frame
  const size_t out_frames =
      static_cast<size_t>(std::floor(static_cast<double>(source_frames - 1) / ratio + 1e-9)) + 1;
  out.fps = target_fps;
  out.root_positions.resize(out_frames);
  out.rotations.resize(out_frames * joint_count);
  for (size_t frame_idx = 0; frame_idx < out_frames; ++frame_idx) {
    const double source_time = static_cast<double>(frame_idx) * ratio;
    const size_t lower = std::min(static_cast<size_t>(source_time), source_frames - 1);
    const size_t upper = std::min(lower + 1, source_frames - 1);
    const double alpha = source_time - static_cast<double>(lower);
    out.root_positions[frame_idx] =
        (1.0 - alpha) * take.root_positions[lower] + alpha * take.root_positions[upper];
    for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
      out.rotation(frame_idx, joint_idx) =
          take.rotation(lower, joint_idx).slerp(alpha, take.rotation(upper, joint_idx));
    }
  }
  return out;
}

}  // namespace motif
