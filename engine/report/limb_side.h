// Which side of the body a joint is on, from its name, and the colour each side is drawn in:
// the one place both the report's keyframe strips (stick_figure_svg.h) and its player
// (instance_playback.h, instance_player_script.h) take their left / right from, so the two
// cannot disagree. Left limbs are blue, right limbs red, the spine and head grey.
// Thread-safety: pure functions and constants.
#pragma once

#include <cstdint>
#include <string>

namespace motif {

enum class LimbSide : uint8_t { kCentre = 0, kLeft = 1, kRight = 2 };
inline constexpr int kLimbSideCount = 3;

// Side of a joint from its name: 1 left, 2 right, 0 centre. Understood (a namespace prefix up to
// the last ':' or '|' ignored, "mixamorig:LeftArm"):
//  * a word: "Left..." / "Right..." in any case ("LeftUpLeg", "leftEye", "RIGHTFOOT");
//  * a tag after or before a separator (_ . - space): "UpperArm_L", "Hand.R", "L_Knee";
//  * one letter L / R / l / r before a capitalised word ("LHipJoint", "RThumb", Daz's
//    "lThigh", "rCollar"), but not an all-capitals name ("ROOT");
//  * CMU's lower-case l / r before the bone ("lfemur", "rhumerus"), except "root" and the
//    "lower..." names ("lowerback", "lowerneck").
uint8_t JointSide(const std::string& name);

// The stroke colour of a side ("#555", "#1f6fd1", "#d62728"), as SVG and canvas take it.
const char* LimbSideColour(uint8_t side);

// ["#555","#1f6fd1","#d62728"]: the colours by side, for a page's script.
std::string LimbSideColoursJson();

}  // namespace motif
