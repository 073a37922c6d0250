#include "engine/cluster/held_pose.h"

#include "engine/distance/pose_features.h"

namespace motif {

Result<std::vector<bool>> FindHeldPoses(const FrameFileReader& archive,
                                        const std::vector<MotifInstance>& instances, float eps) {
  MOTIF_ASSIGN_OR_RETURN(const std::vector<float> weights,
                         LoadDistanceWeights(archive.skeleton(), ""));
  const uint32_t joint_count = archive.layout().joint_count;
  std::vector<bool> held(instances.size(), false);
  std::vector<float> rows;
  for (size_t instance_idx = 0; instance_idx < instances.size(); ++instance_idx) {
    const MotifInstance& instance = instances[instance_idx];
    if (instance.end > archive.frame_count() || instance.end <= instance.start) {
      return Status::InvalidArgument("held poses: instance [" + std::to_string(instance.start) +
                                     ", " + std::to_string(instance.end) +
                                     ") is not a frame range of the archive");
    }
    MOTIF_RETURN_IF_ERROR(archive.ReadFrames(instance.start, instance.length(), &rows));
    const PoseFeatures features =
        PoseFeatures::FromRows(rows.data(), instance.length(), joint_count, weights, {0});
    const uint64_t middle = instance.length() / 2;
    bool within = true;
    for (uint64_t frame_idx = 0; frame_idx < instance.length() && within; ++frame_idx) {
      within = PoseDistance(features, middle, frame_idx) <= eps;
    }
    held[instance_idx] = within;
  }
  return held;
}

}  // namespace motif
