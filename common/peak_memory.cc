#include "common/peak_memory.h"

#include <fstream>
#include <string>

namespace motif {

uint64_t PeakResidentBytes() { return ProcessStatusBytes("VmHWM:"); }

uint64_t ProcessStatusBytes(const std::string& wanted) {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == wanted) {
      uint64_t kilobytes = 0;
      status >> kilobytes;
      return kilobytes * 1024;
    }
    std::getline(status, key);
  }
  return 0;
}

}  // namespace motif
