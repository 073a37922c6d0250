#include "formats/import/amc_parser.h"

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "formats/import/text_scanner.h"
#include "formats/motion/quaternion_math.h"

namespace motif {
namespace {

using import_internal::EqualsIgnoreCase;
using import_internal::kMaxRotationDegrees;
using import_internal::LineCursor;
using import_internal::NextWord;
using import_internal::ParseDouble;
using import_internal::ParseInt64;
using import_internal::Printable;
using import_internal::Quoted;

constexpr int kMaxDofs = 7;  // rx ry rz tx ty tz l

// The root (index 0) or a bone (index k + 1 for bone k), as the AMC lines name it.
struct Entity {
  std::string_view name;
  std::vector<AsfDof> dofs;
  Eigen::Quaterniond axis_rotation;
  Eigen::Quaterniond axis_rotation_inverse;
};

bool IsRotationDof(AsfDof dof) {
  return dof == AsfDof::kRx || dof == AsfDof::kRy || dof == AsfDof::kRz;
}

std::string DofList(const std::vector<AsfDof>& dofs) {
  static const char* kNames[] = {"rx", "ry", "rz", "tx", "ty", "tz", "l"};
  std::string text;
  for (AsfDof dof : dofs) {
    if (!text.empty()) text.push_back(' ');
    text += kNames[static_cast<int>(dof)];
  }
  return text.empty() ? "none" : text;
}

class AmcParser {
 public:
  AmcParser(const AsfSkeleton& asf, std::string_view text, const std::string& file_name)
      : asf_(asf), lines_(text), file_name_(file_name) {
    entities_.push_back(
        {"root", asf.root_order, asf.root_axis_rotation, asf.root_axis_rotation.conjugate()});
    for (const AsfBone& bone : asf.bones) {
      entities_.push_back(
          {bone.name, bone.dofs, bone.axis_rotation, bone.axis_rotation.conjugate()});
    }
    seen_in_frame_.assign(entities_.size(), -1);
    degrees_ = asf.angles_in_degrees;
  }

  Result<Take> Parse(double fps) {
    Take take;
    take.source_path = file_name_;
    take.fps = fps;
    take.source_fps = fps;
    take.meters_per_unit = asf_.meters_per_unit;
    take.skeleton = AsfToSkeleton(asf_);
    take_ = &take;
    std::string_view line;
    while (lines_.Next(&line)) {
      std::string_view rest = line;
      std::string_view word;
      if (!NextWord(&rest, &word) || word[0] == '#') continue;
      if (word[0] == ':') {
        if (frame_count_ > 0) {
          return Error(Quoted(word) + " after the first frame");
        }
        if (EqualsIgnoreCase(word, ":DEGREES")) degrees_ = true;
        if (EqualsIgnoreCase(word, ":RADIANS")) degrees_ = false;
        continue;  // :FULLY-SPECIFIED and other notes
      }
      int64_t frame_number = 0;
      if (ParseInt64(word, &frame_number)) {
        std::string_view extra;
        if (NextWord(&rest, &extra)) {
          return Error("a frame number line holds only the number, found " + Quoted(extra) +
                       " after it");
        }
        MOTIF_RETURN_IF_ERROR(StartFrame(frame_number));
        continue;
      }
      MOTIF_RETURN_IF_ERROR(ParseBoneLine(word, rest));
    }
    if (frame_count_ == 0) return Error("no frames (expected a frame number line)");
    MOTIF_RETURN_IF_ERROR(CheckFrameComplete());
    return take;
  }

 private:
  Status Error(const std::string& problem) const {
    return Status::InvalidArgument(file_name_ + ":" + std::to_string(lines_.line_number()) + ": " +
                                   problem);
  }

  // Every entity with dofs must have appeared in the frame just read.
  Status CheckFrameComplete() const {
    for (size_t entity_idx = 0; entity_idx < entities_.size(); ++entity_idx) {
      if (!entities_[entity_idx].dofs.empty() && seen_in_frame_[entity_idx] != frame_count_ - 1) {
        return Status::InvalidArgument(file_name_ + ":" + std::to_string(frame_line_) + ": frame " +
                                       std::to_string(frame_number_) + " has no line for bone '" +
                                       Printable(entities_[entity_idx].name) +
                                       "' (truncated file?)");
      }
    }
    return Status::Ok();
  }

  Status StartFrame(int64_t frame_number) {
    if (frame_count_ > 0) {
      MOTIF_RETURN_IF_ERROR(CheckFrameComplete());
      // Checked first: no frame can follow the largest int64 (frame_number_ + 1 overflows).
      if (frame_number_ == std::numeric_limits<int64_t>::max() ||
          frame_number != frame_number_ + 1) {
        return Error("frame number " + std::to_string(frame_number) + " follows frame " +
                     std::to_string(frame_number_) + ": frame numbers must be consecutive");
      }
    }
    frame_number_ = frame_number;
    frame_line_ = lines_.line_number();
    ++frame_count_;
    take_->root_positions.push_back(asf_.root_position);
    take_->rotations.resize(take_->rotations.size() + entities_.size(),
                            Eigen::Quaterniond::Identity());
    return Status::Ok();
  }

  int FindEntity(std::string_view name) {
    // Bones usually come in the same order every frame: try the one after the last first.
    const int guess = (last_entity_ + 1) % static_cast<int>(entities_.size());
    if (entities_[guess].name == name) return guess;
    for (size_t entity_idx = 0; entity_idx < entities_.size(); ++entity_idx) {
      if (entities_[entity_idx].name == name) return static_cast<int>(entity_idx);
    }
    return -1;
  }

  Status ParseBoneLine(std::string_view name, std::string_view rest) {
    if (frame_count_ == 0) {
      return Error("expected a frame number before the bone line " + Quoted(name));
    }
    const int entity_idx = FindEntity(name);
    if (entity_idx < 0) {
      return Error("bone " + Quoted(name) + " is not in the skeleton " + asf_.file_name);
    }
    last_entity_ = entity_idx;
    const Entity& entity = entities_[entity_idx];
    if (seen_in_frame_[entity_idx] == frame_count_ - 1) {
      return Error("bone " + Quoted(name) + " appears twice in frame " +
                   std::to_string(frame_number_));
    }
    seen_in_frame_[entity_idx] = frame_count_ - 1;
    std::array<double, kMaxDofs> values{};
    size_t count = 0;
    std::string_view word;
    while (NextWord(&rest, &word)) {
      if (count < entity.dofs.size() && !ParseDouble(word, &values[count])) {
        return Error("bone " + Quoted(name) + ", value " + std::to_string(count + 1) + ": " +
                     Quoted(word) + " is not a finite number");
      }
      ++count;
    }
    if (count != entity.dofs.size()) {
      return Error("bone " + Quoted(name) + " has " + std::to_string(count) + " values in frame " +
                   std::to_string(frame_number_) + ", the ASF gives it " +
                   std::to_string(entity.dofs.size()) + " dofs (" + DofList(entity.dofs) + ")");
    }
    const size_t frame_idx = static_cast<size_t>(frame_count_ - 1);
    Eigen::Quaterniond motion = Eigen::Quaterniond::Identity();
    for (size_t dof_idx = 0; dof_idx < entity.dofs.size(); ++dof_idx) {
      const AsfDof dof = entity.dofs[dof_idx];
      const double value = values[dof_idx];
      if (IsRotationDof(dof)) {
        if (std::abs(degrees_ ? value : value * 180 / M_PI) > kMaxRotationDegrees) {
          return Error("bone " + Quoted(name) + ", value " + std::to_string(dof_idx + 1) +
                       ": a rotation beyond the 1e6 degrees a take can hold");
        }
        const Axis axis = static_cast<Axis>(static_cast<int>(dof) - static_cast<int>(AsfDof::kRx));
        // The first-listed dof is applied first: later ones multiply from the left.
        motion = AxisRotation(axis, degrees_ ? DegreesToRadians(value) : value) * motion;
      } else if (entity_idx == 0 && dof != AsfDof::kLength) {
        take_->root_positions[frame_idx][static_cast<int>(dof) - static_cast<int>(AsfDof::kTx)] =
            value;
      }
    }
    take_->rotation(frame_idx, entity_idx) =
        (entity.axis_rotation * motion * entity.axis_rotation_inverse).normalized();
    return Status::Ok();
  }

  const AsfSkeleton& asf_;
  LineCursor lines_;
  const std::string& file_name_;
  std::vector<Entity> entities_;
  std::vector<int64_t> seen_in_frame_;  // per entity: the last frame index it appeared in
  Take* take_ = nullptr;
  bool degrees_ = true;
  int64_t frame_count_ = 0;
  int64_t frame_number_ = 0;
  int frame_line_ = 0;
  int last_entity_ = 0;
};

}  // namespace

Result<Take> ParseAmc(const AsfSkeleton& asf, std::string_view text, const std::string& file_name,
                      double fps) {
  if (!(fps > 0)) {
    return Status::InvalidArgument(file_name + ": the AMC frame rate must be > 0, got " +
                                   std::to_string(fps));
  }
  AmcParser parser(asf, text, file_name);
  return parser.Parse(fps);
}

}  // namespace motif
