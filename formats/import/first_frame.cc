#include "formats/import/first_frame.h"

#include <algorithm>
#include <vector>

#include "formats/motion/quaternion_math.h"

namespace motif {

double FramePoseDistance(const Take& take, size_t frame_a, size_t frame_b) {
  double distance = 0;
  for (size_t joint_idx = 0; joint_idx < take.joint_count(); ++joint_idx) {
    distance +=
        QuaternionDistance(take.rotation(frame_a, joint_idx), take.rotation(frame_b, joint_idx));
  }
  return distance;
}

FirstFrameCheck CheckFirstFrame(const Take& take) {
  FirstFrameCheck check;
  const size_t frame_count = take.frame_count();
  if (frame_count < kFirstFrameMinFrames || take.joint_count() == 0) return check;
  std::vector<double> steps(frame_count - 1);  // steps[k]: frame k to k + 1
  for (size_t frame_idx = 0; frame_idx + 1 < frame_count; ++frame_idx) {
    steps[frame_idx] = FramePoseDistance(take, frame_idx, frame_idx + 1);
  }
  std::vector<double> later(steps.begin() + 1, steps.end());
  auto middle = later.begin() + later.size() / 2;
  std::nth_element(later.begin(), middle, later.end());
  check.median_step = *middle;
  const double typical_limit = kFirstFrameStepRatio * check.median_step;
  for (size_t start = 1; start <= kFirstFrameMaxBodyStart; ++start) {
    if (start + kFirstFrameBodySteps > steps.size()) break;
    bool typical = true;
    for (size_t step = start; step < start + kFirstFrameBodySteps; ++step) {
      typical = typical && steps[step] <= typical_limit;
    }
    if (typical) {
      check.body_start = start;
      break;
    }
  }
  check.first_jump = FramePoseDistance(take, 0, check.body_start);
  check.discontinuous = check.first_jump > typical_limit && check.first_jump > kFirstFrameMinJump;
  return check;
}

void DropFirstFrame(Take* take) {
  if (take->frame_count() == 0) return;
  take->root_positions.erase(take->root_positions.begin());
  const auto joint_count = static_cast<std::ptrdiff_t>(take->joint_count());
  take->rotations.erase(take->rotations.begin(), take->rotations.begin() + joint_count);
}

}  // namespace motif
