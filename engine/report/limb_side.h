// The colour each side of the body is drawn in, the side of a joint being JointSide of its name
// (formats/motion/joint_side.h, the rule the mapping of other skeleton families reads too): the
// one place both the report's keyframe strips (stick_figure_svg.h) and its player
// (instance_playback.h, instance_player_script.h) take their left / right from, so the two
// cannot disagree. Left limbs are blue, right limbs red, the spine and head grey.
// Thread-safety: pure functions and constants.
#pragma once

#include <cstdint>
#include <string>

#include "formats/motion/joint_side.h"

namespace motif {

inline constexpr int kLimbSideCount = 3;  // BodySide's values, the indices of the colours

// The stroke colour of a side ("#555", "#1f6fd1", "#d62728"), as SVG and canvas take it.
const char* LimbSideColour(uint8_t side);

// ["#555","#1f6fd1","#d62728"]: the colours by side, for a page's script.
std::string LimbSideColoursJson();

}  // namespace motif
