#include "engine/graph/walk_take.h"

#include <cmath>

#include "formats/frame_file/clip_range_take.h"

namespace motif {
namespace {

Result<Take> ReadPiece(const FrameFileReader& reader, const WalkPiece& piece) {
  if (piece.clip >= reader.clips().size()) {
    return Status::InvalidArgument("walk: clip index " + std::to_string(piece.clip));
  }
  return ReadClipRangeAsTake(reader, reader.clips()[piece.clip], piece.start, piece.end);
}

// Turns and moves `take` so that its frame 0 root stands at `position` (on the floor) facing
// `heading`.
void Place(const Eigen::Vector3d& position, double heading, Take* take) {
  const Eigen::Vector3d origin = take->root_positions[0];
  const Eigen::Quaterniond turn(
      Eigen::AngleAxisd(heading - Heading(take->rotation(0, 0)), Eigen::Vector3d::UnitY()));
  for (size_t frame = 0; frame < take->frame_count(); ++frame) {
    Eigen::Vector3d offset = take->root_positions[frame] - origin;
    offset.y() = 0;
    const Eigen::Vector3d moved = turn * offset;
    take->root_positions[frame] = {position.x() + moved.x(), take->root_positions[frame].y(),
                                   position.z() + moved.z()};
    take->rotation(frame, 0) = (turn * take->rotation(frame, 0)).normalized();
  }
}

}  // namespace

double Heading(const Eigen::Quaterniond& root) {
  const Eigen::Vector3d forward = root * Eigen::Vector3d::UnitZ();
  return std::atan2(forward.x(), forward.z());
}

Result<Take> WalkTake(const FrameFileReader& reader, const std::vector<WalkPiece>& pieces,
                      uint32_t window_frames) {
  if (pieces.empty()) return Status::InvalidArgument("walk: no piece");
  MOTIF_ASSIGN_OR_RETURN(Take walk, ReadPiece(reader, pieces[0]));
  walk.name = "walk";
  const size_t joints = walk.joint_count();
  for (size_t idx = 1; idx < pieces.size(); ++idx) {
    MOTIF_ASSIGN_OR_RETURN(Take next, ReadPiece(reader, pieces[idx]));
    if (next.frame_count() < window_frames || walk.frame_count() < window_frames) {
      return Status::InvalidArgument("walk: a piece shorter than the blend window");
    }
    const size_t base = walk.frame_count() - window_frames;
    Place(walk.root_positions[base], Heading(walk.rotation(base, 0)), &next);
    for (size_t k = 0; k < window_frames; ++k) {
      const double alpha = static_cast<double>(k + 1) / (window_frames + 1);
      walk.root_positions[base + k] =
          (1 - alpha) * walk.root_positions[base + k] + alpha * next.root_positions[k];
      for (size_t joint = 0; joint < joints; ++joint) {
        walk.rotation(base + k, joint) =
            walk.rotation(base + k, joint).slerp(alpha, next.rotation(k, joint)).normalized();
      }
    }
    walk.root_positions.insert(walk.root_positions.end(),
                               next.root_positions.begin() + window_frames,
                               next.root_positions.end());
    walk.rotations.insert(
        walk.rotations.end(),
        next.rotations.begin() + static_cast<std::ptrdiff_t>(window_frames * joints),
        next.rotations.end());
  }
  return walk;
}

}  // namespace motif
