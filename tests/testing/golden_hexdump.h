// The annotated hexdumps of docs/formats/*.md, where each format's spec shows a worked example
// byte for byte between the markers below. Golden tests print one from the writer's bytes
// (MOTIF_UPDATE_GOLDEN) and read one back to compare with them.
#pragma once

#include <cstddef>
#include <sstream>
#include <string>

namespace motif::testing {

inline constexpr char kGoldenBegin[] = "<!-- golden-hexdump:begin -->";
inline constexpr char kGoldenEnd[] = "<!-- golden-hexdump:end -->";

// Lines "offset: hh hh ..." of bytes [offset, offset + size), 16 a line; `note` goes on the
// first line after a "| ".
void DumpHexLines(const std::string& bytes, size_t offset, size_t size, const std::string& note,
                  std::ostringstream* out);

// The bytes of the hexdump in `spec_path` ("#" lines are comments, offsets must follow each
// other). "" with *error set if the markers are missing or the offsets do not follow.
std::string BytesFromSpecHexdump(const std::string& spec_path, std::string* error);

// The golden check of a spec's worked example: with MOTIF_UPDATE_GOLDEN=1 in the environment,
// prints `dump` (an annotated hexdump, fenced) to paste between the markers; then expects the
// text between the markers of `spec_path` to be `dump` exactly, and its bytes to be `bytes`.
void ExpectSpecHexdump(const std::string& spec_path, const std::string& dump,
                       const std::string& bytes);

}  // namespace motif::testing
