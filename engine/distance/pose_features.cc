#include "engine/distance/pose_features.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "common/file_util.h"

namespace motif {
namespace {

int16_t Quantise(float value) {
  const float scaled = std::round(std::clamp(value, -1.0f, 1.0f) * PoseFeatures::kQuantScale);
  return static_cast<int16_t>(scaled);
}

}  // namespace

Result<PoseFeatures> PoseFeatures::FromArchive(
    const FrameFileReader& reader, const std::vector<float>& joint_weights,
    const std::function<void(uint64_t, uint64_t)>& progress, RankGroup* ranks) {
  const FrameLayout layout = reader.layout();
  if (joint_weights.size() != layout.joint_count) {
    return Status::InvalidArgument(
        "pose distance weights: " + std::to_string(joint_weights.size()) + " weights for " +
        std::to_string(layout.joint_count) + " joints");
  }
  PoseFeatures features;
  for (uint32_t joint_idx = 0; joint_idx < layout.joint_count; ++joint_idx) {
    if (joint_weights[joint_idx] > 0) {
      features.joints_.push_back(joint_idx);
      features.weights_.push_back(joint_weights[joint_idx]);
    }
  }
  if (features.weights_.empty()) {
    return Status::InvalidArgument("pose distance weights: no joint has a positive weight");
  }
  for (const ClipInfo& clip : reader.clips())
    features.clip_first_frames_.push_back(clip.first_frame);
  if (features.clip_first_frames_.empty()) features.clip_first_frames_.push_back(0);
  const uint64_t frame_count = reader.frame_count();
  features.frame_count_ = frame_count;
  features.values_.resize(frame_count * 4 * features.joints_.size());
  // Shares on block boundaries of the archive, so that no block is decoded twice.
  const RankShare share =
      ShareOf(frame_count, ranks, std::max<uint32_t>(1, reader.summary().block_frames));
  MOTIF_RETURN_IF_ERROR(features.DecodeFrames(reader, share.first(), share.end(), progress));
  if (share.shared()) {
    MOTIF_RETURN_IF_ERROR(ranks->ShareParts(
        features.values_.data(), 4 * features.joints_.size() * sizeof(int16_t), share.starts));
  }
  return features;
}

Status PoseFeatures::DecodeFrames(const FrameFileReader& reader, uint64_t first_frame,
                                  uint64_t end_frame,
                                  const std::function<void(uint64_t, uint64_t)>& progress) {
  const FrameLayout layout = reader.layout();
  const size_t per_frame = 4 * joints_.size();
  std::unique_ptr<FrameStream> stream = reader.Stream(first_frame, end_frame);
  const size_t stride = layout.stride();
  while (true) {
    MOTIF_ASSIGN_OR_RETURN(bool more, stream->Next());
    if (!more) break;
    for (uint64_t offset = 0; offset < stream->frame_count(); ++offset) {
      const float* row = stream->rows() + offset * stride;
      int16_t* out = &values_[(stream->first_frame() + offset) * per_frame];
      for (uint32_t joint : joints_) {
        const float* q = row + layout.quaternion_offset(joint);
        for (int component = 0; component < 4; ++component) *out++ = Quantise(q[component]);
      }
    }
    if (progress) progress(stream->first_frame() + stream->frame_count(), frame_count_);
  }
  return Status::Ok();
}

Result<PoseFeatures> PoseFeatures::ExtendFromArchive(
    PoseFeatures prefix, const FrameFileReader& reader, const std::vector<float>& joint_weights,
    const std::function<void(uint64_t, uint64_t)>& progress) {
  std::vector<uint32_t> joints;
  std::vector<float> weights;
  for (uint32_t joint_idx = 0; joint_idx < joint_weights.size(); ++joint_idx) {
    if (joint_weights[joint_idx] > 0) {
      joints.push_back(joint_idx);
      weights.push_back(joint_weights[joint_idx]);
    }
  }
  if (joint_weights.size() != reader.layout().joint_count || joints != prefix.joints_ ||
      weights != prefix.weights_) {
    return Status::InvalidArgument("pose features: the saved features have other joint weights");
  }
  if (reader.frame_count() < prefix.frame_count_) {
    return Status::InvalidArgument("pose features: " + std::to_string(prefix.frame_count_) +
                                   " saved frames, the archive has " +
                                   std::to_string(reader.frame_count()));
  }
  const uint64_t first_new = prefix.frame_count_;
  prefix.frame_count_ = reader.frame_count();
  prefix.values_.resize(prefix.frame_count_ * 4 * prefix.joints_.size());
  prefix.clip_first_frames_.clear();
  for (const ClipInfo& clip : reader.clips()) prefix.clip_first_frames_.push_back(clip.first_frame);
  if (prefix.clip_first_frames_.empty()) prefix.clip_first_frames_.push_back(0);
  MOTIF_RETURN_IF_ERROR(prefix.DecodeFrames(reader, first_new, prefix.frame_count_, progress));
  return prefix;
}

Result<PoseFeatures> PoseFeatures::FromParts(uint64_t frame_count, std::vector<float> weights,
                                             std::vector<uint32_t> joints,
                                             std::vector<uint64_t> clip_first_frames,
                                             const int16_t* values) {
  if (weights.empty() || weights.size() != joints.size() || clip_first_frames.empty() ||
      clip_first_frames[0] != 0 ||
      !std::is_sorted(clip_first_frames.begin(), clip_first_frames.end())) {
    return Status::InvalidArgument("pose features: malformed saved parts");
  }
  PoseFeatures features;
  features.frame_count_ = frame_count;
  features.weights_ = std::move(weights);
  features.joints_ = std::move(joints);
  features.clip_first_frames_ = std::move(clip_first_frames);
  // `values` may point into a mapped file at any offset: copied bytewise, never dereferenced
  // as int16_t (a misaligned access is undefined behaviour).
  features.values_.resize(frame_count * 4 * features.weights_.size());
  if (!features.values_.empty()) {  // an empty archive may come with no values at all
    std::memcpy(features.values_.data(), values, features.values_.size() * sizeof(int16_t));
  }
  return features;
}

PoseFeatures PoseFeatures::FromRows(const float* rows, uint64_t frame_count, uint32_t joint_count,
                                    const std::vector<float>& joint_weights,
                                    std::vector<uint64_t> clip_first_frames) {
  MOTIF_CHECK(joint_weights.size() == joint_count);
  const FrameLayout layout{joint_count};
  PoseFeatures features;
  for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    if (joint_weights[joint_idx] > 0) {
      features.joints_.push_back(joint_idx);
      features.weights_.push_back(joint_weights[joint_idx]);
    }
  }
  features.frame_count_ = frame_count;
  features.clip_first_frames_ = std::move(clip_first_frames);
  if (features.clip_first_frames_.empty()) features.clip_first_frames_.push_back(0);
  const size_t per_frame = 4 * features.joints_.size();
  features.values_.resize(frame_count * per_frame);
  for (uint64_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    const float* row = rows + frame_idx * layout.stride();
    int16_t* out = &features.values_[frame_idx * per_frame];
    for (uint32_t joint : features.joints_) {
      for (int component = 0; component < 4; ++component) {
        *out++ = Quantise(row[layout.quaternion_offset(joint) + component]);
      }
    }
  }
  return features;
}

uint32_t PoseFeatures::ClipOf(uint64_t frame_idx) const {
  auto after = std::upper_bound(clip_first_frames_.begin(), clip_first_frames_.end(), frame_idx);
  return static_cast<uint32_t>(after - clip_first_frames_.begin()) - 1;
}

float PoseDistance(const PoseFeatures& features, uint64_t frame_a, uint64_t frame_b) {
  const int16_t* a = features.frame(frame_a);
  const int16_t* b = features.frame(frame_b);
  float total = 0;
  const uint32_t joint_count = features.weighted_joint_count();
  for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    total += features.weights()[joint_idx] * JointTerm(a, b, joint_idx);
  }
  return total;
}

Result<std::vector<float>> LoadDistanceWeights(const Skeleton& skeleton,
                                               const std::string& weights_path) {
  std::vector<float> weights;
  for (const Joint& joint : skeleton.joints()) weights.push_back(joint.weight);
  if (weights_path.empty()) return weights;
  MOTIF_ASSIGN_OR_RETURN(std::string text, ReadFileToString(weights_path));
  std::istringstream lines(text);
  std::string line;
  for (int line_number = 1; std::getline(lines, line); ++line_number) {
    const size_t comment = line.find('#');
    if (comment != std::string::npos) line.resize(comment);
    std::istringstream fields(line);
    std::string name;
    std::string value;
    if (!(fields >> name)) continue;  // blank line
    const std::string where = weights_path + ":" + std::to_string(line_number) + ": ";
    std::string extra;
    if (!(fields >> value) || (fields >> extra)) {
      return Status::InvalidArgument(where + "expected \"joint_name weight\"");
    }
    const int joint_idx = skeleton.FindJoint(name);
    if (joint_idx < 0) {
      return Status::InvalidArgument(where + "no joint named '" + name + "' in the archive's " +
                                     skeleton.family() + " skeleton");
    }
    char* end = nullptr;
    const double weight = std::strtod(value.c_str(), &end);
    if (end == value.c_str() || *end != '\0' || !std::isfinite(weight) || weight < 0) {
      return Status::InvalidArgument(where + "weight '" + value + "' is not a non-negative number");
    }
    weights[joint_idx] = static_cast<float>(weight);
  }
  return weights;
}

}  // namespace motif
