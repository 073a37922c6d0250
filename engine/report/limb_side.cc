#include "engine/report/limb_side.h"

#include <cctype>

namespace motif {
namespace {

constexpr const char* kColours[kLimbSideCount] = {"#555", "#1f6fd1", "#d62728"};

bool IsSeparator(char c) { return c == '_' || c == '.' || c == '-' || c == ' '; }
bool IsUpper(char c) { return std::isupper(static_cast<unsigned char>(c)) != 0; }
bool IsLower(char c) { return std::islower(static_cast<unsigned char>(c)) != 0; }

bool StartsWithWord(const std::string& name, const char* word) {
  size_t idx = 0;
  for (; word[idx] != '\0'; ++idx) {
    if (idx >= name.size() || std::tolower(static_cast<unsigned char>(name[idx])) != word[idx]) {
      return false;
    }
  }
  return true;
}

// 1 / 2 for the tag letter l / r (any case), else 0.
uint8_t SideOfLetter(char c) {
  const char lower = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower == 'l' ? 1 : lower == 'r' ? 2 : 0;
}

}  // namespace

uint8_t JointSide(const std::string& full_name) {
  const size_t namespace_end = full_name.find_last_of(":|");
  const std::string name =
      namespace_end == std::string::npos ? full_name : full_name.substr(namespace_end + 1);
  const size_t size = name.size();
  if (StartsWithWord(name, "left")) return 1;
  if (StartsWithWord(name, "right")) return 2;
  if (size >= 3 && IsSeparator(name[size - 2]) && SideOfLetter(name[size - 1]) != 0) {
    return SideOfLetter(name[size - 1]);  // "UpperArm_L", "hand.r"
  }
  if (size >= 3 && IsSeparator(name[1]) && SideOfLetter(name[0]) != 0) {
    return SideOfLetter(name[0]);  // "L_Knee"
  }
  if (size >= 3 && SideOfLetter(name[0]) != 0 && IsUpper(name[1]) && IsLower(name[2])) {
    return SideOfLetter(name[0]);  // "LHipJoint", "lThigh"
  }
  // CMU: a lower-case l or r before the bone's name ("lfemur", "rhumerus", "lhipjoint").
  if (size > 2 && (name[0] == 'l' || name[0] == 'r') && IsLower(name[1]) && name != "root" &&
      name.rfind("lower", 0) != 0) {
    return name[0] == 'l' ? 1 : 2;
  }
  return 0;
}

const char* LimbSideColour(uint8_t side) { return kColours[side < kLimbSideCount ? side : 0]; }

std::string LimbSideColoursJson() {
  std::string json = "[";
  for (int side = 0; side < kLimbSideCount; ++side) {
    json += std::string(side ? "," : "") + "\"" + kColours[side] + "\"";
  }
  return json + "]";
}

}  // namespace motif
