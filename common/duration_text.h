// A length of time as a person writes it, for summaries and the report.
// Thread-safety: a pure function.
#pragma once

#include <string>

namespace motif {

// "1.2 s" under a minute, "4.3 min" under an hour, "2.5 h" above ("0.0 min" for a 148-frame take
// said nothing).
std::string FormatDuration(double seconds);

}  // namespace motif
