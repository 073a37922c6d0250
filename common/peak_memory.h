// The process's peak resident memory, for the summaries and reports that state it.
#pragma once

#include <cstdint>

namespace motif {

// VmHWM of /proc/self/status in bytes; 0 where it cannot be read.
uint64_t PeakResidentBytes();

}  // namespace motif
