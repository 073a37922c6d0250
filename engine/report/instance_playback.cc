#include "engine/report/instance_playback.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <boost/archive/iterators/base64_from_binary.hpp>
#include <boost/archive/iterators/transform_width.hpp>

#include "engine/report/forward_kinematics.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/quaternion_math.h"

namespace motif {

uint32_t PlaybackStep(double fps) {
  return static_cast<uint32_t>(std::max(1.0, std::round(fps / kPlaybackFps)));
}

std::string Base64(const uint8_t* bytes, size_t size) {
  using Encoder = boost::archive::iterators::base64_from_binary<
      boost::archive::iterators::transform_width<const uint8_t*, 6, 8>>;
  std::string text(Encoder(bytes), Encoder(bytes + size));  // the last group zero-padded
  text.append((3 - size % 3) % 3, '=');
  return text;
}

InstancePlayback::InstancePlayback(const FrameFileReader& reader, const StickFigureLayout& layout)
    : reader_(reader), layout_(layout), cache_(reader) {
  step_ = PlaybackStep(reader.fps());
  height_ = std::max(1e-9, RestPoseExtent(reader.skeleton()));
}

Result<PlaybackInstance> InstancePlayback::Encode(const ClipInfo& clip, uint64_t start,
                                                  uint64_t end) {
  PlaybackInstance instance;
  instance.start = start;
  instance.end = end;
  instance.samples = static_cast<uint32_t>((end - start - 1) / step_ + 1);
  // Consecutive frames, so that the root's path integrates as in the clip.
  MOTIF_ASSIGN_OR_RETURN(const float* rows,
                         cache_.Rows(clip.first_frame + start, clip.first_frame + end));
  const size_t stride = cache_.stride();
  const Take take = ClipFramesToTake(reader_.skeleton(), clip, rows, end - start);
  std::vector<Eigen::Vector3d> points;
  points.reserve(static_cast<size_t>(instance.samples) * layout_.points.size());
  double floor = std::numeric_limits<double>::max();
  instance.sample_rows.reserve(static_cast<size_t>(instance.samples) * stride);
  for (uint32_t sample = 0; sample < instance.samples; ++sample) {
    const float* row = &rows[static_cast<size_t>(sample) * step_ * stride];
    instance.sample_rows.insert(instance.sample_rows.end(), row, row + stride);
    const std::vector<Eigen::Vector3d> pose =
        TakeFramePositions(take, static_cast<size_t>(sample) * step_);
    for (uint32_t point : layout_.points) {
      points.push_back(pose[point]);
      floor = std::min(floor, pose[point].y());
    }
  }
  const Eigen::Vector3d origin(take.root_positions[0].x(), floor, take.root_positions[0].z());
  double reach = 1e-9;
  for (Eigen::Vector3d& point : points) {
    point -= origin;
    reach = std::max(reach, point.cwiseAbs().maxCoeff());
  }
  instance.origin = {origin.x(), origin.y(), origin.z()};
  instance.scale = 32000.0 / reach;
  instance.heading_rad = HeadingOf(take.rotation(0, 0));
  std::vector<uint8_t> bytes;
  bytes.reserve(points.size() * 6);
  for (const Eigen::Vector3d& point : points) {
    for (int axis = 0; axis < 3; ++axis) {
      const auto value = static_cast<int16_t>(std::lround(point[axis] * instance.scale));
      const auto bits = static_cast<uint16_t>(value);
      bytes.push_back(static_cast<uint8_t>(bits & 0xff));
      bytes.push_back(static_cast<uint8_t>(bits >> 8));
    }
  }
  instance.points_base64 = Base64(bytes.data(), bytes.size());
  return instance;
}

std::string InstancePlayback::FigureJson() const {
  std::string json = "{\"step\":" + std::to_string(step_) + ",\"fps\":";
  char number[32];
  std::snprintf(number, sizeof(number), "%g", reader_.fps());
  json += number;
  std::snprintf(number, sizeof(number), "%.6g", height_);
  // The root's position among the layout's points (the view follows it); 0 if it is not drawn.
  const auto root = std::find(layout_.points.begin(), layout_.points.end(), 0u);
  const size_t root_idx = root == layout_.points.end() ? 0 : root - layout_.points.begin();
  json += ",\"height\":" + std::string(number) + ",\"root\":" + std::to_string(root_idx) +
          ",\"sides\":[";
  // The strips' sides and colours (stick_figure_svg.h), so the player and they agree.
  for (size_t idx = 0; idx < layout_.points.size(); ++idx) {
    if (idx) json += ',';
    json += std::to_string(layout_.sides.empty() ? 0 : layout_.sides[idx]);
  }
  json += "],\"colours\":" + LimbSideColoursJson() + ",\"chains\":[";
  for (size_t chain = 0; chain < layout_.chains.size(); ++chain) {
    json += chain ? ",[" : "[";
    for (size_t idx = 0; idx < layout_.chains[chain].size(); ++idx) {
      if (idx) json += ',';
      json += std::to_string(layout_.chains[chain][idx]);
    }
    json += "]";
  }
  return json + "]}";
}

}  // namespace motif
