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

using RotationOrders = std::vector<std::array<Axis, 3>>;  // per joint

// "ROOT name" or "JOINT name", its brace, OFFSET and CHANNELS lines.
void AppendJointHeader(const Joint& joint, bool root, const std::array<Axis, 3>& order, int depth,
                       std::string* out) {
  AppendIndent(depth, out);
  out->append(root ? "ROOT " : "JOINT ").append(joint.name).append("\n");
  AppendIndent(depth, out);
  out->append("{\n");
  AppendOffset(joint.offset, depth + 1, out);
  AppendIndent(depth + 1, out);
  out->append(root ? "CHANNELS 6 Xposition Yposition Zposition" : "CHANNELS 3");
  for (Axis axis : order) out->append(" ").append(RotationChannelName(axis));
  out->push_back('\n');
}

// The joint's End Site (if it has one) and its closing brace.
void AppendJointEnd(const Joint& joint, int depth, std::string* out) {
  if (joint.has_end_site) {
    AppendIndent(depth, out);
    out->append("End Site\n");
    AppendIndent(depth, out);
    out->append("{\n");
    AppendOffset(joint.end_site, depth + 1, out);
    AppendIndent(depth, out);
    out->append("}\n");
  }
  AppendIndent(depth - 1, out);
  out->append("}\n");
}

// The hierarchy, depth first (children in joint order); returns the joints in the order they
// were written, which is the order of the channels in every frame line.
std::vector<int> AppendHierarchy(const Skeleton& skeleton, const RotationOrders& orders,
                                 std::string* out) {
  const size_t joint_count = skeleton.joint_count();
  std::vector<std::vector<int>> children(joint_count);
  for (size_t joint_idx = 1; joint_idx < joint_count; ++joint_idx) {
    const int parent = skeleton.joint(joint_idx).parent;
    if (parent >= 0 && static_cast<size_t>(parent) < joint_count) {
      children[parent].push_back(static_cast<int>(joint_idx));
    }
  }
  std::vector<int> write_order;
  if (joint_count == 0) return write_order;
  struct Frame {
    int joint_idx;
    size_t next_child;
  };
  std::vector<Frame> stack = {{0, 0}};
  AppendJointHeader(skeleton.joint(0), /*root=*/true, orders[0], 0, out);
  write_order.push_back(0);
  while (!stack.empty()) {
    Frame& top = stack.back();
    const int depth = static_cast<int>(stack.size());
    if (top.next_child < children[top.joint_idx].size()) {
      const int child = children[top.joint_idx][top.next_child++];
      AppendJointHeader(skeleton.joint(child), /*root=*/child == 0, orders[child], depth, out);
      write_order.push_back(child);
      stack.push_back({child, 0});
      continue;
    }
    AppendJointEnd(skeleton.joint(top.joint_idx), depth, out);
    stack.pop_back();
  }
  return write_order;
}

// "MOTION", the frame count and the frame time (120 fps for a take without a rate).
void AppendMotionHeader(const Take& take, std::string* out) {
  out->append("MOTION\nFrames: ").append(std::to_string(take.frame_count())).append("\n");
  char frame_time[64];
  const double fps = take.fps > 0 ? take.fps : 120.0;
  std::snprintf(frame_time, sizeof(frame_time), "%.9g", 1.0 / fps);
  out->append("Frame Time: ").append(frame_time).append("\n");
}

// One line a frame: the root's position, then every joint's Euler angles in degrees, continuous
// (each joint's previous frame seeds QuaternionToEuler).
void AppendFrames(const Take& take, const std::vector<int>& write_order,
                  const RotationOrders& orders, std::string* out) {
  const size_t joint_count = take.skeleton.joint_count();
  const size_t frame_count = take.frame_count();
  std::vector<std::array<double, 3>> previous(joint_count, {0, 0, 0});
  out->reserve(out->size() + frame_count * (6 + 3 * joint_count) * 12);
  for (size_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    const Eigen::Vector3d& position = take.root_positions[frame_idx];
    bool first_value = true;
    auto append_value = [&](double value) {
      if (!first_value) out->push_back(' ');
      first_value = false;
      AppendNumber(value, out);
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
    out->push_back('\n');
  }
}

}  // namespace

std::string FormatBvh(const Take& take) {
  const Skeleton& skeleton = take.skeleton;
  RotationOrders orders(skeleton.joint_count());
  for (size_t joint_idx = 0; joint_idx < skeleton.joint_count(); ++joint_idx) {
    orders[joint_idx] = RotationOrder(skeleton.joint(joint_idx));
  }
  std::string out = "HIERARCHY\n";
  const std::vector<int> write_order = AppendHierarchy(skeleton, orders, &out);
  AppendMotionHeader(take, &out);
  AppendFrames(take, write_order, orders, &out);
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
