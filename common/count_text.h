// Counts as a person writes them, for summaries, notes and the report.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>

namespace motif {

// Thousands separators: 40346 -> "40,346".
std::string WithCommas(uint64_t value);

// "1 clip", "1,234 clips": a count with commas and its noun, plural when it is not 1 (nouns that
// take an "s").
std::string CountOf(uint64_t count, const std::string& noun);

}  // namespace motif
