// Take: one imported motion clip in memory, as the importers produce it and before it is
// converted to the archive's per-frame columns (pose_frames.h). Rotations are unit quaternions
// of each joint relative to its parent, expressed in a frame aligned with the skeleton's rest
// pose (for ASF/AMC: the AMC rotation conjugated by the bone's axis rotation, C * R * C^-1), so
// takes from BVH and ASF/AMC files are comparable. The root rotation is the full world rotation.
// A take is at most a few minutes of motion, so it is held whole; archives are not.
// Thread-safety: a value type.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "formats/motion/skeleton.h"

namespace motif {

struct Take {
  std::string name;            // the source file's stem, e.g. "05_01" or "07_05-walk"
  std::string source_path;     // as given to the importer
  double fps = 120.0;          // frames per second of `root_positions` / `rotations`
  double source_fps = 120.0;   // the rate of the source file before any resampling
  double meters_per_unit = 0;  // length unit in metres when the source says (ASF), 0 if unknown
  uint64_t content_hash = 0;   // XXH3-64 of the source file bytes (identifies a take on re-import)
  // Where frame 0 is in the source file: the 0-based index of that frame among the file's frames
  // (1 when the importer dropped a converter's T-pose). Resampled takes: source frame
  // source_first_frame + k * source_fps / fps is frame k.
  uint64_t source_first_frame = 0;
  // The source file's name of each joint (skeleton order) when the importer renamed them (a BVH
  // take's "LeftUpLeg" is the canonical "lfemur"); empty when the names are the source's.
  std::vector<std::string> source_joint_names;
  std::string description;  // what the take shows, from an index the user gave; may be empty
  Skeleton skeleton;
  std::vector<Eigen::Vector3d> root_positions;  // per frame, world, source length units
  std::vector<Eigen::Quaterniond> rotations;    // frame-major: [frame * joint_count + joint]

  size_t frame_count() const { return root_positions.size(); }
  size_t joint_count() const { return skeleton.joint_count(); }
  const Eigen::Quaterniond& rotation(size_t frame_idx, size_t joint_idx) const {
    return rotations[frame_idx * skeleton.joint_count() + joint_idx];
  }
  Eigen::Quaterniond& rotation(size_t frame_idx, size_t joint_idx) {
    return rotations[frame_idx * skeleton.joint_count() + joint_idx];
  }
};

}  // namespace motif
