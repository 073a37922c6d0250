#include "engine/cluster/instance_samples.h"

#include <algorithm>

#include "engine/cluster/held_pose.h"
#include "engine/cluster/instance_rows.h"

namespace motif {

Result<InstanceSamples> ReadInstanceSamples(const FrameFileReader& archive,
                                            const std::vector<MotifInstance>& instances,
                                            uint32_t samples, float eps, int threads) {
  if (samples < 2) return Status::InvalidArgument("instance samples: at least 2 an instance");
  MOTIF_ASSIGN_OR_RETURN(const std::vector<float> weights,
                         LoadDistanceWeights(archive.skeleton(), ""));
  const uint32_t joint_count = archive.layout().joint_count;
  const uint64_t stride = archive.layout().stride();
  InstanceSamples result;
  result.first = {0};
  for (const MotifInstance& instance : instances) {
    result.first.push_back(result.first.back() + std::min<uint64_t>(samples, instance.length()));
  }
  result.held.assign(instances.size(), 0);
  std::vector<float> sampled(result.first.back() * stride);
  // Each instance writes only its own samples and flag: safe from any thread.
  MOTIF_RETURN_IF_ERROR(ForEachInstanceRows(
      archive, instances,
      [&](size_t idx, const float* rows) {
        const uint64_t length = instances[idx].length();
        const uint64_t count = result.first[idx + 1] - result.first[idx];
        for (uint64_t sample = 0; sample < count; ++sample) {
          const uint64_t frame = count == 1 ? 0 : sample * (length - 1) / (count - 1);
          std::copy(rows + frame * stride, rows + (frame + 1) * stride,
                    sampled.begin() +
                        static_cast<std::ptrdiff_t>((result.first[idx] + sample) * stride));
        }
        const PoseFeatures frames = PoseFeatures::FromRows(rows, length, joint_count, weights, {0});
        result.held[idx] = IsHeldPose(frames, length, eps) ? 1 : 0;
        return Status::Ok();
      },
      threads));
  result.features =
      PoseFeatures::FromRows(sampled.data(), result.first.back(), joint_count, weights, {0});
  return result;
}

}  // namespace motif
