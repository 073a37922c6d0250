#include "common/count_text.h"

namespace motif {

std::string WithCommas(uint64_t value) {
  std::string digits = std::to_string(value);
  std::string out;
  for (size_t idx = 0; idx < digits.size(); ++idx) {
    if (idx > 0 && (digits.size() - idx) % 3 == 0) out += ',';
    out += digits[idx];
  }
  return out;
}

std::string CountOf(uint64_t count, const std::string& noun) {
  return WithCommas(count) + " " + noun + (count == 1 ? "" : "s");
}

}  // namespace motif
