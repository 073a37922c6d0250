// A random walk's pieces (motion_graph.h) played as one take, for walk.bvh:
//  * each piece is read from the archive as a take (world root trajectory, the clip's own bone
//    lengths); the walk keeps the first piece's skeleton;
//  * each later piece is turned about the vertical axis and moved on the floor so that its first
//    frame's root stands where, and faces where, the first frame of the previous piece's last
//    window_frames frames does (the root's height is its own);
//  * over those window_frames frames the two are blended: frame k of the window takes
//    alpha = (k + 1) / (window_frames + 1) of the new piece (root position linearly, every joint
//    rotation by slerp), then the new piece goes on alone.
// So the root is continuous at every junction, and the take has WalkFrames(pieces) frames.
// Thread-safety: a pure function (the reader's const methods are thread-safe).
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "engine/graph/motion_graph.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/motion/take.h"

namespace motif {

// InvalidArgument: no piece, a piece outside its clip, a later piece shorter than the window.
// Errors of the reader pass through.
Result<Take> WalkTake(const FrameFileReader& reader, const std::vector<WalkPiece>& pieces,
                      uint32_t window_frames);

// The heading (rotation about +Y, radians) of a root rotation: where its local +Z points on the
// floor.
double Heading(const Eigen::Quaterniond& root);

}  // namespace motif
