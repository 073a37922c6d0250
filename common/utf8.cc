#include "common/utf8.h"

#include <cstdint>

namespace motif {

bool IsValidUtf8(std::string_view text) {
  size_t at = 0;
  while (at < text.size()) {
    const auto lead = static_cast<uint8_t>(text[at]);
    size_t extra = 0;
    uint32_t code = 0;
    uint32_t least = 0;  // the smallest code point this length may encode (no overlong forms)
    if (lead < 0x80) {
      ++at;
      continue;
    } else if ((lead & 0xe0) == 0xc0) {
      extra = 1, code = lead & 0x1f, least = 0x80;
    } else if ((lead & 0xf0) == 0xe0) {
      extra = 2, code = lead & 0x0f, least = 0x800;
    } else if ((lead & 0xf8) == 0xf0) {
      extra = 3, code = lead & 0x07, least = 0x10000;
    } else {
      return false;  // a continuation byte first, or 0xf8..0xff
    }
    if (text.size() - at <= extra) return false;
    for (size_t idx = 1; idx <= extra; ++idx) {
      const auto byte = static_cast<uint8_t>(text[at + idx]);
      if ((byte & 0xc0) != 0x80) return false;
      code = (code << 6) | (byte & 0x3f);
    }
    if (code < least || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff)) return false;
    at += extra + 1;
  }
  return true;
}

}  // namespace motif
