// UTF-8 validity: names that reach JSON outputs (clip names from file names, joint names from
// take files, source paths) must be valid UTF-8, or the JSON written from them is not valid JSON
// and readers fail (the JSON library throws on dump).
#pragma once

#include <string_view>

namespace motif {

// True if `text` is well-formed UTF-8 (RFC 3629): no stray continuation bytes, no overlong
// forms, no surrogates (U+D800..U+DFFF), nothing above U+10FFFF.
bool IsValidUtf8(std::string_view text);

}  // namespace motif
