// The process's peak resident memory, for the summaries and reports that state it.
#pragma once

#include <cstdint>
#include <string>

namespace motif {

// A "<key> <n> kB" line of /proc/self/status in bytes ("VmHWM:", "RssFile:"); 0 where it
// cannot be read.
uint64_t ProcessStatusBytes(const std::string& key);

// VmHWM of /proc/self/status in bytes; 0 where it cannot be read.
uint64_t PeakResidentBytes();

}  // namespace motif
