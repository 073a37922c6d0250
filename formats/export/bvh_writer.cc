#include "formats/export/bvh_writer.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <vector>

#include "common/file_util.h"
#include "formats/motion/quaternion_math.h"

namespace motif {
namespace {

bool IsRotation(ChannelType type) {
  return type == ChannelType::kXRotation || type == ChannelType::kYRotation ||
         type == ChannelType::kZRotation;
}

// The joint's three rotation axes in composition order: its stored rotation channels when they
// name three distinct axes, ZYX otherwise.
std::array<Axis, 3> RotationOrder(const Joint& joint) {
  std::array<Axis, 3> order{};
  int count = 0;
  for (ChannelType type : joint.channels) {
    if (!IsRotation(type)) continue;
    if (count == 3) return {Axis::kZ, Axis::kY, Axis::kX};
    order[count++] =
        static_cast<Axis>(static_cast<int>(type) - static_cast<int>(ChannelType::kXRotation));
  }
  if (count != 3 || order[0] == order[1] || order[1] == order[2] || order[0] == order[2]) {
    return {Axis::kZ, Axis::kY, Axis::kX};
  }
  return order;
}

const char* RotationChannelName(Axis axis) {
  switch (axis) {
    case Axis::kX:
      return "Xrotation";
    case Axis::kY:
      return "Yrotation";
    case Axis::kZ:
      return "Zrotation";
  }
  return "Xrotation";
}

// Fixed-point with 6 decimals (1e-6 degree is far below any capture's precision); never
// "-0.000000", so unchanged channels diff cleanly.
void AppendNumber(double value, std::string* out) {
  char buffer[64];
  auto [end, error] =
      std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::fixed, 6);
  if (error != std::errc()) {
    out->append("0.000000");
    return;
  }
  std::string_view text(buffer, end - buffer);
  if (text == "-0.000000") text = text.substr(1);
  out->append(text);
}

void AppendIndent(int depth, std::string* out) { out->append(static_cast<size_t>(depth), '\t'); }

void AppendOffset(const std::array<double, 3>& offset, int depth, std::string* out) {
  AppendIndent(depth, out);
  out->append("OFFSET");
  for (double value : offset) {
    out->push_back(' ');
    AppendNumber(value, out);
  }
  out->push_back('\n');
}

}  // namespace

std::string FormatBvh(const Take& take) {
  const Skeleton& skeleton = take.skeleton;
  const size_t joint_count = skeleton.joint_count();
  std::vector<std::vector<int>> children(joint_count);
  for (size_t joint_idx = 1; joint_idx < joint_count; ++joint_idx) {
    const int parent = skeleton.joint(joint_idx).parent;
    if (parent >= 0 && static_cast<size_t>(parent) < joint_count) {
      children[parent].push_back(static_cast<int>(joint_idx));
    }
  }
  std::vector<std::array<Axis, 3>> orders(joint_count);
  for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    orders[joint_idx] = RotationOrder(skeleton.joint(joint_idx));
  }

  // Hierarchy, depth first: the order of the channels in every frame line.
  std::string out = "HIERARCHY\n";
  std::vector<int> write_order;
  if (joint_count > 0) {
    struct Frame {
      int joint_idx;
      size_t next_child;
    };
    std::vector<Frame> stack = {{0, 0}};
    auto open_joint = [&](int joint_idx, int depth) {
      const Joint& joint = skeleton.joint(joint_idx);
      AppendIndent(depth, &out);
      out.append(joint_idx == 0 ? "ROOT " : "JOINT ").append(joint.name).append("\n");
      AppendIndent(depth, &out);
      out.append("{\n");
      AppendOffset(joint.offset, depth + 1, &out);
      AppendIndent(depth + 1, &out);
      out.append(joint_idx == 0 ? "CHANNELS 6 Xposition Yposition Zposition" : "CHANNELS 3");
      for (Axis axis : orders[joint_idx]) out.append(" ").append(RotationChannelName(axis));
      out.push_back('\n');
      write_order.push_back(joint_idx);
    };
    open_joint(0, 0);
    while (!stack.empty()) {
      Frame& top = stack.back();
      const int depth = static_cast<int>(stack.size());
      if (top.next_child < children[top.joint_idx].size()) {
        const int child = children[top.joint_idx][top.next_child++];
        open_joint(child, depth);
        stack.push_back({child, 0});
        continue;
      }
      const Joint& joint = skeleton.joint(top.joint_idx);
      if (joint.has_end_site) {
        AppendIndent(depth, &out);
        out.append("End Site\n");
        AppendIndent(depth, &out);
        out.append("{\n");
        AppendOffset(joint.end_site, depth + 1, &out);
        AppendIndent(depth, &out);
        out.append("}\n");
      }
      AppendIndent(depth - 1, &out);
      out.append("}\n");
      stack.pop_back();
    }
  }

  const size_t frame_count = take.frame_count();
  out.append("MOTION\nFrames: ").append(std::to_string(frame_count)).append("\n");
  char frame_time[64];
  const double fps = take.fps > 0 ? take.fps : 120.0;
  std::snprintf(frame_time, sizeof(frame_time), "%.9g", 1.0 / fps);
  out.append("Frame Time: ").append(frame_time).append("\n");

  // Continuous Euler angles: each joint's previous frame seeds QuaternionToEuler.
  std::vector<std::array<double, 3>> previous(joint_count, {0, 0, 0});
  out.reserve(out.size() + frame_count * (6 + 3 * joint_count) * 12);
  for (size_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    const Eigen::Vector3d& position = take.root_positions[frame_idx];
    bool first_value = true;
    auto append_value = [&](double value) {
      if (!first_value) out.push_back(' ');
      first_value = false;
      AppendNumber(value, &out);
    };
    for (int joint_idx : write_order) {
      if (joint_idx == 0) {
        for (int axis = 0; axis < 3; ++axis) append_value(position[axis]);
      }
      const std::array<double, 3> angles = QuaternionToEuler(
          take.rotation(frame_idx, joint_idx), orders[joint_idx], previous[joint_idx]);
      previous[joint_idx] = angles;
      for (double angle : angles) append_value(RadiansToDegrees(angle));
    }
    out.push_back('\n');
  }
  return out;
}

Status WriteBvh(const Take& take, const std::string& path) {
  Status valid = take.skeleton.Validate();
  if (!valid.ok())
    return Status::InvalidArgument(path + ": cannot write take '" + take.name +
                                   "': " + valid.message());
  if (take.rotations.size() != take.frame_count() * take.joint_count()) {
    return Status::InvalidArgument(path + ": cannot write take '" + take.name + "': it has " +
                                   std::to_string(take.rotations.size()) + " rotations for " +
                                   std::to_string(take.frame_count()) + " frames of " +
                                   std::to_string(take.joint_count()) + " joints");
  }
  return AtomicWriteFile(path, FormatBvh(take));
}

}  // namespace motif
