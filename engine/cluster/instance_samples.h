// What the cluster stage reads of each instance's frames, read once: evenly spaced samples as pose
// features (the warped distances of warped_similarity.h and the representatives of
// motif_representatives.h compare them) and whether the instance is a held pose (held_pose.h).
// Each of the three used to decode the archive's blocks under the instances again; at 10^6
// frames the decoding was more than half of the cluster stage (docs/benchmarks.md, "Incremental
// reindexing"). The spans of instances are decoded in parallel.
// Thread-safety: pure function; the reader may be shared.
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "engine/cluster/motif_instance.h"
#include "engine/distance/pose_features.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

struct InstanceSamples {
  // The samples of every instance, one after another: min(samples, length) frames of each,
  // evenly spaced, its first and last frame included; the skeleton's default joint weights.
  PoseFeatures features;
  std::vector<uint64_t> first;  // first[i]: instance i's first sample; first.back() the total
  // Per instance: 1 if it is a held pose at eps (IsHeldPose, held_pose.h: its frames all within
  // eps of its middle frame).
  std::vector<uint8_t> held;
};

// `samples` at least 2. InvalidArgument for an instance outside the archive or empty; reader
// errors pass through (the first in instance order). The same bits for any thread count
// (threads 0: all cores).
Result<InstanceSamples> ReadInstanceSamples(const FrameFileReader& archive,
                                            const std::vector<MotifInstance>& instances,
                                            uint32_t samples, float eps, int threads);

}  // namespace motif
