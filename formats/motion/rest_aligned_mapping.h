// The mapping onto the CMU body for a rig whose zero rotations stand upright (a T- or A-pose:
// CMU's, Daz's): each canonical joint of the torso takes its source joint's world rotation times
// a constant correction, the rotation that turns the canonical rest bone onto the source's rest
// bone once the two rest body frames (up to the chest, left across the hips) are aligned. The
// canonical joints without a source joint are left to the caller (body_retarget.h).
// Thread-safety: immutable once built.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "formats/motion/body_landmarks.h"

namespace motif {

// True when the rig's zero rotations stand upright: the chest within 45 degrees of straight
// above the pelvis, each ankle within 45 degrees of straight below its hip. `rest`: the rig's
// joint positions at zero rotations.
bool StandsUprightAtRest(const BodyLandmarks& body, const std::vector<Eigen::Vector3d>& rest);

class RestAlignedMapping {
 public:
  // `source_rest`, `canonical_rest`: joint positions at zero rotations of the source rig and of
  // the CMU rest body.
  RestAlignedMapping(const BodyLandmarks& body, const std::vector<Eigen::Vector3d>& source_rest,
                     const std::vector<Eigen::Vector3d>& canonical_rest);

  // Sets the world rotation of each canonical joint that has a source joint (and its flag in
  // `set`), for a frame whose source world rotations are `source_world`.
  void Pose(const std::vector<Eigen::Quaterniond>& source_world,
            std::vector<Eigen::Quaterniond>* world, std::vector<bool>* set) const;

 private:
  std::vector<int> source_of_;  // per canonical joint, its source joint or -1
  std::vector<Eigen::Quaterniond> corrections_;
};

}  // namespace motif
