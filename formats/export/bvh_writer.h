// Writing a Take as a BVH file that opens in Blender and other BVH viewers: the skeleton's
// hierarchy with its offsets and end sites, the root with 6 channels (positions, then rotations)
// and every other joint with 3 rotation channels, in each joint's stored channel order (ZYX when
// none is stored), angles in degrees, continuous from frame to frame.
// Thread-safety: pure functions.
#pragma once

#include <string>

#include "common/status.h"
#include "formats/motion/take.h"

namespace motif {

// The BVH text for `take`.
std::string FormatBvh(const Take& take);

// Writes FormatBvh(take) to `path` atomically. IOError / ResourceExhausted.
Status WriteBvh(const Take& take, const std::string& path);

}  // namespace motif
