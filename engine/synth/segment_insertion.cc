#include "engine/synth/segment_insertion.h"

#include <algorithm>
#include <numbers>
#include <random>

#include "formats/motion/quaternion_math.h"

namespace motif {

Segment WarpSegment(const Take& source, size_t start, size_t frames, size_t out_frames,
                    const std::function<double(size_t)>& source_time) {
  const size_t joints = source.joint_count();
  Segment segment;
  for (size_t out = 0; out < out_frames; ++out) {
    const double time = std::clamp(source_time(out), 0.0, static_cast<double>(frames - 1)) +
                        static_cast<double>(start);
    const size_t lo = std::min(static_cast<size_t>(time), source.frame_count() - 2);
    const double weight = time - static_cast<double>(lo);
    for (size_t joint = 0; joint < joints; ++joint) {
      const Eigen::Quaterniond a = source.rotation(lo, joint);
      const Eigen::Quaterniond b = AlignSign(source.rotation(lo + 1, joint), a);
      segment.rotations.push_back(a.slerp(weight, b).normalized());
    }
    segment.root_positions.push_back((1 - weight) * source.root_positions[lo] +
                                     weight * source.root_positions[lo + 1]);
  }
  return segment;
}

void AddSmoothNoise(Segment* segment, double degrees, size_t spacing, uint64_t seed) {
  const size_t frames = segment->frame_count();
  if (frames == 0 || degrees <= 0) return;
  const size_t joints = segment->rotations.size() / frames;
  const size_t keys = frames / std::max<size_t>(spacing, 1) + 2;
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal(0.0, degrees * std::numbers::pi / 180.0);
  std::vector<Eigen::Vector3d> key_noise(keys * joints);
  for (Eigen::Vector3d& noise : key_noise) noise = {normal(random), normal(random), normal(random)};
  for (size_t frame = 0; frame < frames; ++frame) {
    const double position = static_cast<double>(frame) / static_cast<double>(spacing);
    const size_t key = static_cast<size_t>(position);
    const double weight = position - static_cast<double>(key);
    for (size_t joint = 0; joint < joints; ++joint) {
      const Eigen::Vector3d noise = (1 - weight) * key_noise[key * joints + joint] +
                                    weight * key_noise[(key + 1) * joints + joint];
      Eigen::Quaterniond& rotation = segment->rotations[frame * joints + joint];
      const double angle = noise.norm();
      if (angle > 0) rotation = (rotation * Eigen::AngleAxisd(angle, noise / angle)).normalized();
    }
  }
}

Take InsertSegment(const Take& host, size_t at, const Segment& segment) {
  Take result = host;
  const size_t joints = host.joint_count();
  result.rotations.clear();
  result.root_positions.clear();
  result.rotations.insert(result.rotations.end(), host.rotations.begin(),
                          host.rotations.begin() + static_cast<std::ptrdiff_t>(at * joints));
  result.root_positions.insert(result.root_positions.end(), host.root_positions.begin(),
                               host.root_positions.begin() + static_cast<std::ptrdiff_t>(at));
  Eigen::Vector3d shift = host.root_positions[at] - segment.root_positions.front();
  shift.y() = 0;
  result.rotations.insert(result.rotations.end(), segment.rotations.begin(),
                          segment.rotations.end());
  for (const Eigen::Vector3d& position : segment.root_positions) {
    result.root_positions.push_back(position + shift);
  }
  Eigen::Vector3d rest_shift = result.root_positions.back() - host.root_positions[at];
  rest_shift.y() = 0;
  result.rotations.insert(result.rotations.end(),
                          host.rotations.begin() + static_cast<std::ptrdiff_t>(at * joints),
                          host.rotations.end());
  for (size_t frame = at; frame < host.frame_count(); ++frame) {
    result.root_positions.push_back(host.root_positions[frame] + rest_shift);
  }
  return result;
}

}  // namespace motif
