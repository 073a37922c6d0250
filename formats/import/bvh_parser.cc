#include "formats/import/bvh_parser.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "formats/import/animated_root.h"
#include "formats/import/text_scanner.h"
#include "formats/motion/quaternion_math.h"

namespace motif {
namespace {

using import_internal::EqualsIgnoreCase;
using import_internal::IsBlank;
using import_internal::LineCursor;
using import_internal::kMaxRotationDegrees;
using import_internal::ParseDouble;
using import_internal::ParseInt64;
using import_internal::Printable;
using import_internal::Quoted;
using import_internal::Token;
using import_internal::Tokenizer;

// Where a joint's channels sit in a frame line, precomputed so the frame loop does no lookups.
struct JointLayout {
  int rotation_count = 0;
  std::array<Axis, 3> rotation_axes{};
  std::array<int, 3> rotation_channel{};  // index into the frame's values
};

// Where each value of a frame line goes.
struct BvhFrameLayout {
  std::vector<JointLayout> joints;
  // The position channels of the root chain's joints (RootChainMotion); -1: the joint's OFFSET.
  std::vector<std::array<int, 3>> chain_position_channel;
  int channel_count = 0;
};

// State of a joint while its braces are open.
struct OpenJoint {
  int joint_idx = 0;
  int open_line = 0;
  bool has_offset = false;
  bool has_channels = false;
};

bool IsRotation(ChannelType type) {
  return type == ChannelType::kXRotation || type == ChannelType::kYRotation ||
         type == ChannelType::kZRotation;
}

Axis AxisOf(ChannelType type) {
  switch (type) {
    case ChannelType::kXPosition:
    case ChannelType::kXRotation:
      return Axis::kX;
    case ChannelType::kYPosition:
    case ChannelType::kYRotation:
      return Axis::kY;
    case ChannelType::kZPosition:
    case ChannelType::kZRotation:
      return Axis::kZ;
  }
  return Axis::kX;
}

// Matches "<word0> <word1> ... :" at the start of `line` (case-insensitive, blanks allowed
// around the words and the colon); on success `*value` is the trimmed text after the colon.
bool MatchLabel(std::string_view line, std::initializer_list<std::string_view> words,
                std::string_view* value) {
  size_t pos = 0;
  auto skip_blanks = [&] {
    while (pos < line.size() && IsBlank(line[pos])) ++pos;
  };
  for (std::string_view word : words) {
    skip_blanks();
    if (line.size() - pos < word.size() || !EqualsIgnoreCase(line.substr(pos, word.size()), word)) {
      return false;
    }
    pos += word.size();
  }
  skip_blanks();
  if (pos >= line.size() || line[pos] != ':') return false;
  ++pos;
  skip_blanks();
  size_t end = line.size();
  while (end > pos && IsBlank(line[end - 1])) --end;
  *value = line.substr(pos, end - pos);
  return true;
}

bool IsBlankLine(std::string_view line) {
  return std::all_of(line.begin(), line.end(), [](char c) { return IsBlank(c); });
}

class BvhParser {
 public:
  BvhParser(std::string_view text, const std::string& file_name)
      : tokenizer_(text), file_name_(file_name) {}

  // The HIERARCHY alone: the file's skeleton, before any root is moved.
  Result<Skeleton> ParseSkeleton() {
    MOTIF_RETURN_IF_ERROR(ParseHierarchy());
    Skeleton skeleton("custom", joints_);
    Status valid = skeleton.Validate();
    if (!valid.ok()) return Error(joint_lines_.empty() ? 1 : joint_lines_[0], valid.message());
    return skeleton;
  }

  Result<Take> Parse(double fps_override) {
    MOTIF_RETURN_IF_ERROR(ParseHierarchy());
    Take take;
    take.source_path = file_name_;
    take.skeleton = Skeleton("custom", joints_);
    Status valid = take.skeleton.Validate();
    if (!valid.ok()) return Error(joint_lines_.empty() ? 1 : joint_lines_[0], valid.message());
    RootChainMotion chain;
    MOTIF_RETURN_IF_ERROR(ParseMotion(fps_override, &take, &chain));
    MoveRootBelowStaticJoints(chain, StaticJointsAboveRoot(chain, take), &take);
    return take;
  }

 private:
  Status Error(int line, const std::string& problem) const {
    return Status::InvalidArgument(file_name_ + ":" + std::to_string(line) + ": " + problem);
  }

  // The joint name after ROOT/JOINT: the tokens on the keyword's line up to an optional '{'.
  Status ReadJointName(const Token& keyword, std::string* name) {
    Token token;
    name->clear();
    while (tokenizer_.Peek(&token) && token.line == keyword.line && token.text != "{") {
      tokenizer_.Next(&token);
      if (!name->empty()) name->push_back(' ');
      name->append(token.text);
    }
    if (name->empty()) return Error(keyword.line, std::string(keyword.text) + " without a name");
    return Status::Ok();
  }

  Status Expect(std::string_view wanted, const std::string& context) {
    Token token;
    if (!tokenizer_.Next(&token)) {
      return Error(tokenizer_.last_token_line(), "file ends where " + std::string(wanted) +
                                                     " was expected " + context +
                                                     " (truncated file?)");
    }
    if (!EqualsIgnoreCase(token.text, wanted)) {
      return Error(token.line, "expected '" + std::string(wanted) + "' " + context + ", found " +
                                   Quoted(token.text));
    }
    return Status::Ok();
  }

  Status ReadOffset(const std::string& owner, std::array<double, 3>* offset) {
    for (int axis = 0; axis < 3; ++axis) {
      Token token;
      if (!tokenizer_.Next(&token)) {
        return Error(tokenizer_.last_token_line(), "file ends inside the OFFSET of " + owner);
      }
      if (!ParseDouble(token.text, &(*offset)[axis])) {
        return Error(token.line,
                     "OFFSET of " + owner + " needs 3 finite numbers, found " + Quoted(token.text));
      }
    }
    return Status::Ok();
  }

  Status ReadChannels(const Token& keyword, OpenJoint* open) {
    Joint& joint = joints_[open->joint_idx];
    const std::string owner = "joint '" + Printable(joint.name) + "'";
    if (open->has_channels) return Error(keyword.line, owner + " has two CHANNELS lines");
    open->has_channels = true;
    Token token;
    int64_t count = 0;
    if (!tokenizer_.Next(&token)) return Error(keyword.line, "file ends inside CHANNELS");
    if (!ParseInt64(token.text, &count) || count < 0 || count > 6) {
      return Error(token.line, "CHANNELS of " + owner +
                                   " must start with a count from 0 to 6, found " +
                                   Quoted(token.text));
    }
    for (int64_t channel_idx = 0; channel_idx < count; ++channel_idx) {
      if (!tokenizer_.Next(&token)) return Error(keyword.line, "file ends inside CHANNELS");
      ChannelType type;
      if (!ParseChannelType(std::string(token.text), &type)) {
        return Error(token.line, "CHANNELS of " + owner + " declares " + std::to_string(count) +
                                     " channels, but " + Quoted(token.text) + " (channel " +
                                     std::to_string(channel_idx + 1) + ") is not a channel name");
      }
      if (std::find(joint.channels.begin(), joint.channels.end(), type) != joint.channels.end()) {
        return Error(token.line,
                     "CHANNELS of " + owner + " lists " + ChannelTypeName(type) + " twice");
      }
      joint.channels.push_back(type);
    }
    return Status::Ok();
  }

  Status ReadEndSite(const Token& keyword, OpenJoint* open) {
    Joint& joint = joints_[open->joint_idx];
    Token token;
    if (!tokenizer_.Next(&token) || !EqualsIgnoreCase(token.text, "Site")) {
      return Error(keyword.line, "expected 'End Site'");
    }
    if (joint.has_end_site) {
      return Error(keyword.line, "joint '" + Printable(joint.name) + "' has a second End Site");
    }
    const std::string context = "in the End Site of joint '" + Printable(joint.name) + "'";
    MOTIF_RETURN_IF_ERROR(Expect("{", context));
    MOTIF_RETURN_IF_ERROR(Expect("OFFSET", context));
    MOTIF_RETURN_IF_ERROR(
        ReadOffset("the End Site of joint '" + Printable(joint.name) + "'", &joint.end_site));
    MOTIF_RETURN_IF_ERROR(Expect("}", context));
    joint.has_end_site = true;
    return Status::Ok();
  }

  Status OpenNewJoint(const Token& keyword, int parent) {
    Joint joint;
    joint.parent = parent;
    MOTIF_RETURN_IF_ERROR(ReadJointName(keyword, &joint.name));
    if (joints_.size() >= kMaxSkeletonJoints) {
      return Error(keyword.line, "more than " + std::to_string(kMaxSkeletonJoints) +
                                     " joints, the most an archive holds");
    }
    // A map, not a scan: a hostile file of 100,000 joints took 19 s with the scan.
    const auto [seen, inserted] = joint_index_.emplace(joint.name, joints_.size());
    if (!inserted) {
      return Error(keyword.line, "joint name '" + Printable(joint.name) +
                                     "' is used twice (first at line " +
                                     std::to_string(joint_lines_[seen->second]) + ")");
    }
    MOTIF_RETURN_IF_ERROR(
        Expect("{", "after " + std::string(keyword.text) + " " + Printable(joint.name)));
    stack_.push_back({static_cast<int>(joints_.size()), keyword.line, false, false});
    joints_.push_back(std::move(joint));
    joint_lines_.push_back(keyword.line);
    return Status::Ok();
  }

  Status ParseHierarchy() {
    Token token;
    if (!tokenizer_.Next(&token)) return Error(1, "empty file: expected HIERARCHY");
    if (!EqualsIgnoreCase(token.text, "HIERARCHY")) {
      return Error(token.line,
                   "expected HIERARCHY, found " + Quoted(token.text) + " (not a BVH file?)");
    }
    if (!tokenizer_.Next(&token)) return Error(token.line, "file ends after HIERARCHY");
    if (!EqualsIgnoreCase(token.text, "ROOT")) {
      return Error(token.line, "expected ROOT, found " + Quoted(token.text));
    }
    MOTIF_RETURN_IF_ERROR(OpenNewJoint(token, -1));
    while (!stack_.empty()) {
      OpenJoint& open = stack_.back();
      const std::string owner = "joint '" + Printable(joints_[open.joint_idx].name) + "'";
      if (!tokenizer_.Next(&token)) {
        return Error(tokenizer_.last_token_line(),
                     "file ends inside " + owner + " (opened at line " +
                         std::to_string(open.open_line) + "): unbalanced braces or truncated file");
      }
      if (EqualsIgnoreCase(token.text, "OFFSET")) {
        if (open.has_offset) return Error(token.line, owner + " has two OFFSETs");
        open.has_offset = true;
        MOTIF_RETURN_IF_ERROR(ReadOffset(owner, &joints_[open.joint_idx].offset));
      } else if (EqualsIgnoreCase(token.text, "CHANNELS")) {
        MOTIF_RETURN_IF_ERROR(ReadChannels(token, &open));
      } else if (EqualsIgnoreCase(token.text, "JOINT")) {
        MOTIF_RETURN_IF_ERROR(OpenNewJoint(token, open.joint_idx));
      } else if (EqualsIgnoreCase(token.text, "End")) {
        MOTIF_RETURN_IF_ERROR(ReadEndSite(token, &open));
      } else if (token.text == "}") {
        if (!open.has_offset) return Error(token.line, owner + " has no OFFSET");
        stack_.pop_back();
      } else if (EqualsIgnoreCase(token.text, "MOTION") || EqualsIgnoreCase(token.text, "ROOT")) {
        return Error(token.line, std::string(token.text) + " inside " + owner +
                                     " (opened at line " + std::to_string(open.open_line) +
                                     "): unbalanced braces, a '}' is missing");
      } else {
        return Error(token.line, "unexpected " + Quoted(token.text) + " in " + owner);
      }
    }
    if (!tokenizer_.Next(&token)) {
      return Error(tokenizer_.last_token_line(), "missing MOTION section after the hierarchy");
    }
    if (EqualsIgnoreCase(token.text, "ROOT")) {
      return Error(token.line, "a second ROOT: files with several hierarchies are not supported");
    }
    if (token.text == "}") {
      return Error(token.line, "unbalanced braces: '}' after the root joint was closed");
    }
    if (!EqualsIgnoreCase(token.text, "MOTION")) {
      return Error(token.line, "expected MOTION after the hierarchy, found " + Quoted(token.text));
    }
    motion_line_ = token.line;
    return Status::Ok();
  }

  // Reads the next non-blank line; false at the end of the text.
  static bool NextNonBlank(LineCursor* lines, std::string_view* line) {
    while (lines->Next(line)) {
      if (!IsBlankLine(*line)) return true;
    }
    return false;
  }

  // The channels in the order of a frame line: rotations per joint, the root's position.
  // The file's root and each joint below it that is its parent's only child and has position
  // channels: joints 0 .. count - 1 (depth-first order puts an only child next).
  size_t RootChainLength() const {
    std::vector<int> child_count(joints_.size(), 0);
    for (const Joint& joint : joints_) {
      if (joint.parent >= 0) ++child_count[joint.parent];
    }
    size_t count = 1;
    while (count < joints_.size() && joints_[count].parent == static_cast<int>(count) - 1 &&
           child_count[count - 1] == 1 && HasPositionChannel(joints_[count])) {
      ++count;
    }
    return count;
  }

  static bool HasPositionChannel(const Joint& joint) {
    return std::any_of(joint.channels.begin(), joint.channels.end(),
                       [](ChannelType type) { return !IsRotation(type); });
  }

  BvhFrameLayout BuildFrameLayout() const {
    BvhFrameLayout frame;
    frame.joints.resize(joints_.size());
    frame.chain_position_channel.assign(RootChainLength(), {-1, -1, -1});
    for (size_t joint_idx = 0; joint_idx < joints_.size(); ++joint_idx) {
      for (ChannelType type : joints_[joint_idx].channels) {
        if (IsRotation(type)) {
          JointLayout& layout = frame.joints[joint_idx];
          layout.rotation_axes[layout.rotation_count] = AxisOf(type);
          layout.rotation_channel[layout.rotation_count] = frame.channel_count;
          ++layout.rotation_count;
        } else if (joint_idx < frame.chain_position_channel.size()) {
          frame.chain_position_channel[joint_idx][static_cast<int>(AxisOf(type))] =
              frame.channel_count;
        }
        ++frame.channel_count;
      }
    }
    return frame;
  }

  // The rest of the MOTION line (blank), then 'Frames: <count>'.
  Status ReadFrameCount(LineCursor* lines, int64_t* frame_count) const {
    std::string_view line;
    lines->Next(&line);  // the rest of the MOTION line
    if (!IsBlankLine(line)) {
      return Error(motion_line_, "unexpected " + Quoted(line) + " after MOTION");
    }
    std::string_view value;
    if (!NextNonBlank(lines, &line)) {
      return Error(lines->line_number(), "file ends after MOTION: expected 'Frames:'");
    }
    if (!MatchLabel(line, {"Frames"}, &value)) {
      return Error(lines->line_number(), "expected 'Frames: <count>', found " + Quoted(line));
    }
    if (!ParseInt64(value, frame_count) || *frame_count < 0) {
      return Error(lines->line_number(),
                   "'Frames:' needs a non-negative integer, found " + Quoted(value));
    }
    if (*frame_count == 0) {
      return Error(lines->line_number(), "'Frames: 0': the take has no frames");
    }
    return Status::Ok();
  }

  // 'Frame Time: <seconds>' as a rate (a near-integer rate rounded), unless overridden.
  Status ReadFrameRate(LineCursor* lines, double fps_override, double* fps_out) const {
    std::string_view line;
    std::string_view value;
    if (!NextNonBlank(lines, &line)) {
      return Error(lines->line_number(), "file ends after 'Frames:': expected 'Frame Time:'");
    }
    double frame_time = 0;
    if (!MatchLabel(line, {"Frame", "Time"}, &value)) {
      return Error(lines->line_number(), "expected 'Frame Time: <seconds>', found " + Quoted(line));
    }
    if (!ParseDouble(value, &frame_time)) {
      return Error(lines->line_number(),
                   "'Frame Time:' needs a finite number, found " + Quoted(value));
    }
    if (frame_time <= 0) {
      return Error(lines->line_number(), "'Frame Time: " + Printable(value) + "': must be > 0");
    }
    // A take is resampled to the archive's rate on import: a frame time of hours would turn a
    // few bytes of motion into millions of frames.
    if (frame_time < kMinBvhFrameTime || frame_time > kMaxBvhFrameTime) {
      return Error(lines->line_number(), "'Frame Time: " + Printable(value) +
                                             "': must be between 1e-06 and 1 second (1 to "
                                             "1000000 frames per second)");
    }
    double fps = 1.0 / frame_time;
    const double rounded = std::round(fps);
    if (rounded >= 1 && std::abs(fps - rounded) <= 1e-4 * fps) fps = rounded;
    if (fps_override > 0) fps = fps_override;
    *fps_out = fps;
    return Status::Ok();
  }

  // One frame's values as the root chain's translations, the root position and every joint's
  // rotation.
  void AppendPose(const BvhFrameLayout& frame, const std::vector<double>& values, Take* take,
                  RootChainMotion* chain) const {
    for (size_t joint_idx = 0; joint_idx < frame.chain_position_channel.size(); ++joint_idx) {
      const std::array<double, 3>& offset = joints_[joint_idx].offset;
      Eigen::Vector3d translation;
      for (int axis = 0; axis < 3; ++axis) {
        const int channel = frame.chain_position_channel[joint_idx][axis];
        translation[axis] = channel >= 0 ? values[channel] : offset[axis];
      }
      chain->translations.push_back(translation);
    }
    take->root_positions.push_back(chain->translations[chain->translations.size() - chain->count]);
    for (size_t joint_idx = 0; joint_idx < joints_.size(); ++joint_idx) {
      const JointLayout& layout = frame.joints[joint_idx];
      Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
      for (int rotation_idx = 0; rotation_idx < layout.rotation_count; ++rotation_idx) {
        rotation = rotation *
                   AxisRotation(layout.rotation_axes[rotation_idx],
                                DegreesToRadians(values[layout.rotation_channel[rotation_idx]]));
      }
      take->rotations.push_back(rotation);
    }
  }

  // Every rotation channel of one frame within kMaxRotationDegrees.
  Status CheckRotations(const BvhFrameLayout& frame, const std::vector<double>& values,
                        int line_number, int64_t frame_idx) const {
    for (const JointLayout& layout : frame.joints) {
      for (int rotation_idx = 0; rotation_idx < layout.rotation_count; ++rotation_idx) {
        const int channel = layout.rotation_channel[rotation_idx];
        if (std::abs(values[channel]) <= kMaxRotationDegrees) continue;
        char degrees[32];
        std::snprintf(degrees, sizeof degrees, "%g", values[channel]);
        return Error(line_number, "frame " + std::to_string(frame_idx) + ", value " +
                                      std::to_string(channel + 1) + ": a rotation of " + degrees +
                                      " degrees, beyond the 1e6 degrees a take can hold");
      }
    }
    return Status::Ok();
  }

  // The `frame_count` frame lines declared at line `frames_line`, and not one more.
  Status ReadFrames(const BvhFrameLayout& frame, int64_t frame_count, int frames_line,
                    LineCursor* lines, Take* take, RootChainMotion* chain) const {
    // Never trust the declared count for memory: a damaged header may claim billions.
    const size_t max_plausible = tokenizer_.Rest().size() / (2 * frame.channel_count) + 1;
    const size_t reserve_frames = std::min<size_t>(static_cast<size_t>(frame_count), max_plausible);
    take->root_positions.reserve(reserve_frames);
    take->rotations.reserve(reserve_frames * joints_.size());
    chain->count = frame.chain_position_channel.size();
    chain->translations.reserve(reserve_frames * chain->count);
    std::string_view line;
    std::vector<double> values(frame.channel_count);
    for (int64_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
      if (!NextNonBlank(lines, &line)) {
        return Error(lines->line_number(), "file ends after " + std::to_string(frame_idx) +
                                               " of the " + std::to_string(frame_count) +
                                               " frames declared at line " +
                                               std::to_string(frames_line) + " (truncated file?)");
      }
      MOTIF_RETURN_IF_ERROR(ParseFrameLine(line, lines->line_number(), frame_idx, &values));
      MOTIF_RETURN_IF_ERROR(CheckRotations(frame, values, lines->line_number(), frame_idx));
      AppendPose(frame, values, take, chain);
    }
    if (NextNonBlank(lines, &line)) {
      return Error(lines->line_number(),
                   "more frame lines than the " + std::to_string(frame_count) +
                       " declared by 'Frames:' at line " + std::to_string(frames_line));
    }
    return Status::Ok();
  }

  Status ParseMotion(double fps_override, Take* take, RootChainMotion* chain) {
    const BvhFrameLayout frame = BuildFrameLayout();
    if (frame.channel_count == 0) return Error(motion_line_, "the hierarchy declares no channels");
    LineCursor lines(tokenizer_.Rest(), motion_line_);
    int64_t frame_count = 0;
    MOTIF_RETURN_IF_ERROR(ReadFrameCount(&lines, &frame_count));
    const int frames_line = lines.line_number();
    double fps = 0;
    MOTIF_RETURN_IF_ERROR(ReadFrameRate(&lines, fps_override, &fps));
    take->fps = fps;
    take->source_fps = fps;
    return ReadFrames(frame, frame_count, frames_line, &lines, take, chain);
  }

  Status ParseFrameLine(std::string_view line, int line_number, int64_t frame_idx,
                        std::vector<double>* values) const {
    const size_t channel_count = values->size();
    const char* pos = line.data();
    const char* end = pos + line.size();
    size_t count = 0;
    while (true) {
      while (pos < end && IsBlank(*pos)) ++pos;
      if (pos == end) break;
      const char* start = pos;
      while (pos < end && !IsBlank(*pos)) ++pos;
      if (count >= channel_count) {
        ++count;
        continue;  // count the extra values for the message
      }
      const std::string_view token(start, pos - start);
      if (!ParseDouble(token, &(*values)[count])) {
        return Error(line_number, "frame " + std::to_string(frame_idx) + ", value " +
                                      std::to_string(count + 1) + ": " + Quoted(token) +
                                      " is not a finite number");
      }
      ++count;
    }
    if (count != channel_count) {
      return Error(line_number, "frame " + std::to_string(frame_idx) + " has " +
                                    std::to_string(count) + " values, the hierarchy declares " +
                                    std::to_string(channel_count) + " channels");
    }
    return Status::Ok();
  }

  Tokenizer tokenizer_;
  const std::string& file_name_;
  std::vector<Joint> joints_;
  std::unordered_map<std::string, size_t> joint_index_;  // name -> index into joints_
  std::vector<int> joint_lines_;
  std::vector<OpenJoint> stack_;
  int motion_line_ = 0;
};

}  // namespace

Result<Take> ParseBvh(std::string_view text, const std::string& file_name, double fps_override) {
  BvhParser parser(text, file_name);
  return parser.Parse(fps_override);
}

Result<Skeleton> ParseBvhSkeleton(std::string_view text, const std::string& file_name) {
  BvhParser parser(text, file_name);
  return parser.ParseSkeleton();
}

}  // namespace motif
