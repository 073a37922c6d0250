// The root that moves. Many studio rigs animate `Hips` under a static `joint_Root` (or
// `Reference`) joint that sits at the origin and never moves. The archive takes joint 0 as the
// root for height, velocity, heading removal and export, so such a take would have no root
// motion and keep its heading inside the Hips rotation. The BVH importer therefore records the
// local translation of the joints at the top of the file's hierarchy and, where the file's root
// is static, makes its only child the root: the static joints' constant transform is folded into
// the new root's world position and rotation (exact: nothing is lost), and they leave the
// skeleton. See docs/formats/frame_file.md ("Which joint is the root").
// Thread-safety: pure functions.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "formats/motion/take.h"

namespace motif {

// The file's root and the joints below it, as long as each is the only child of the one above
// and has position channels: joints 0, 1, ..., count - 1 of the take (a depth-first order puts a
// single child right after its parent).
struct RootChainMotion {
  size_t count = 1;
  // Per frame, each chain joint's translation from its parent: its position channels (its
  // OFFSET on an axis without a channel). Frame-major: [frame * count + chain joint].
  std::vector<Eigen::Vector3d> translations;
};

// How many joints of the chain a static chain puts above the joint that moves: the leading
// joints whose translation and rotation are the same in every frame, each with one child that
// has position channels. 0 when the file's root moves (CMU, Daz) or has several children.
size_t StaticJointsAboveRoot(const RootChainMotion& chain, const Take& take);

// Drops the take's first `static_count` joints (StaticJointsAboveRoot), folding their
// transform into the joint below them, which becomes joint 0: its root position is the static
// joints' transform applied to its translation, its rotation their rotation times its own, and
// its OFFSET their transform applied to its own. No-op for 0.
void MoveRootBelowStaticJoints(const RootChainMotion& chain, size_t static_count, Take* take);

}  // namespace motif
