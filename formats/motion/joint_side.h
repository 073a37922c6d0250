// Which side of the body a joint is on, from its name: the one rule that both the mapping of
// other skeleton families onto the CMU body (body_landmarks.h) and the report's left / right
// colours (engine/report/limb_side.h) read, so a joint mapped as a left limb is drawn as one.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace motif {

enum class BodySide : uint8_t { kCentre = 0, kLeft = 1, kRight = 2 };

// A joint name split into its side and the body part it names.
struct SidedJointName {
  BodySide side = BodySide::kCentre;
  std::string part;  // without namespace and side, lower-cased, letters and digits only
};

// The side and part of `name`. Understood (a namespace prefix up to the last ':' or '|'
// ignored, "mixamorig:LeftArm"):
//  * a word: "Left..." / "Right..." in any case ("LeftUpLeg", "leftEye", "RIGHTFOOT");
//  * a tag after or before a separator (_ . - space): "UpperArm_L", "Hand.R", "L_Knee";
//  * one letter L / R / l / r before a capitalised word ("LHipJoint", "RThumb", Daz's
//    "lThigh", "rCollar"), but not an all-capitals name ("ROOT");
//  * CMU's lower-case l / r before the bone ("lfemur", "rhumerus"), except "root" and the
//    "lower..." names ("lowerback", "lowerneck");
//  * only beside one of `known_parts` (parts as SidedJointName::part has them, "upperarm"),
//    since a glued letter or word is also part of many names ("Larynx", "Tail", "Upright"):
//    left / right / l / r in any case before or after it ("UpperArmLeft", "upperarmL", "LARM").
SidedJointName SplitJointSide(const std::string& name, const std::vector<std::string>& known_parts);

// The side of a joint from its name alone (SplitJointSide with no known parts): 1 left,
// 2 right, 0 centre.
uint8_t JointSide(const std::string& name);

}  // namespace motif
