#include "formats/motion/joint_side.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <utility>

namespace motif {
namespace {

// Where a side tag stands in a name: [begin, begin + length).
struct SideTag {
  BodySide side;
  size_t begin;
  size_t length;
};

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

// The side of the tag letter l / r (any case), else centre.
BodySide SideOfLetter(char c) {
  const char lower = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower == 'l' ? BodySide::kLeft : lower == 'r' ? BodySide::kRight : BodySide::kCentre;
}

// The tag `name` (its namespace removed) carries on its own, whatever its part.
std::optional<SideTag> TaggedSide(const std::string& name) {
  const size_t size = name.size();
  if (StartsWithWord(name, "left")) return SideTag{BodySide::kLeft, 0, 4};
  if (StartsWithWord(name, "right")) return SideTag{BodySide::kRight, 0, 5};
  if (size >= 3 && IsSeparator(name[size - 2]) &&
      SideOfLetter(name[size - 1]) != BodySide::kCentre) {
    return SideTag{SideOfLetter(name[size - 1]), size - 2, 2};  // "UpperArm_L", "hand.r"
  }
  if (size >= 3 && IsSeparator(name[1]) && SideOfLetter(name[0]) != BodySide::kCentre) {
    return SideTag{SideOfLetter(name[0]), 0, 2};  // "L_Knee"
  }
  if (size >= 3 && SideOfLetter(name[0]) != BodySide::kCentre && IsUpper(name[1]) &&
      IsLower(name[2])) {
    return SideTag{SideOfLetter(name[0]), 0, 1};  // "LHipJoint", "lThigh"
  }
  // CMU: a lower-case l or r before the bone's name ("lfemur", "rhumerus", "lhipjoint").
  if (size > 2 && (name[0] == 'l' || name[0] == 'r') && IsLower(name[1]) && name != "root" &&
      name.rfind("lower", 0) != 0) {
    return SideTag{SideOfLetter(name[0]), 0, 1};
  }
  return std::nullopt;
}

// Lower case, letters and digits only.
std::string Normalised(const std::string& name) {
  std::string out;
  for (unsigned char c : name) {
    if (std::isalnum(c)) out.push_back(static_cast<char>(std::tolower(c)));
  }
  return out;
}

bool IsKnown(const std::vector<std::string>& parts, const std::string& part) {
  return std::find(parts.begin(), parts.end(), part) != parts.end();
}

// `name` (normalised) as a side glued before or after one of `parts`.
std::optional<SidedJointName> GluedSide(const std::string& name,
                                        const std::vector<std::string>& parts) {
  for (const auto& [tag, side] : {std::pair{std::string("left"), BodySide::kLeft},
                                  std::pair{std::string("right"), BodySide::kRight},
                                  std::pair{std::string("l"), BodySide::kLeft},
                                  std::pair{std::string("r"), BodySide::kRight}}) {
    if (name.size() <= tag.size()) continue;
    const std::string after = name.substr(tag.size());
    const std::string before = name.substr(0, name.size() - tag.size());
    if (name.compare(0, tag.size(), tag) == 0 && IsKnown(parts, after)) return {{side, after}};
    if (name.compare(before.size(), tag.size(), tag) == 0 && IsKnown(parts, before)) {
      return {{side, before}};
    }
  }
  return std::nullopt;
}

}  // namespace

SidedJointName SplitJointSide(const std::string& full_name,
                              const std::vector<std::string>& known_parts) {
  const size_t namespace_end = full_name.find_last_of(":|");
  const std::string name =
      namespace_end == std::string::npos ? full_name : full_name.substr(namespace_end + 1);
  SidedJointName tagged{BodySide::kCentre, Normalised(name)};
  if (const std::optional<SideTag> tag = TaggedSide(name)) {
    tagged = {tag->side, Normalised(std::string(name).erase(tag->begin, tag->length))};
    if (known_parts.empty() || IsKnown(known_parts, tagged.part)) return tagged;
  }
  // A tag beside an unknown part may hide a glued side beside a known one ("lShld_r" is
  // "lshldr"): the glued forms read a name whatever its separators.
  if (std::optional<SidedJointName> glued = GluedSide(Normalised(name), known_parts)) {
    return *glued;
  }
  return tagged;
}

uint8_t JointSide(const std::string& name) {
  return static_cast<uint8_t>(SplitJointSide(name, {}).side);
}

}  // namespace motif
