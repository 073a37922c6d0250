#include "engine/report/limb_side.h"

namespace motif {
namespace {

constexpr const char* kColours[kLimbSideCount] = {"#555", "#1f6fd1", "#d62728"};

}  // namespace

const char* LimbSideColour(uint8_t side) { return kColours[side < kLimbSideCount ? side : 0]; }

std::string LimbSideColoursJson() {
  std::string json = "[";
  for (int side = 0; side < kLimbSideCount; ++side) {
    json += std::string(side ? "," : "") + "\"" + kColours[side] + "\"";
  }
  return json + "]";
}

}  // namespace motif
