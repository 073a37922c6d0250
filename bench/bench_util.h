// Helpers shared by the benchmarks: peak resident memory as a counter, CPU time, and where the
// real CMU takes are. Header-only: each benchmark is its own small program.
#pragma once

#include <sys/resource.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace motif::bench {

// Resets the kernel's peak-RSS mark of this process (Linux: "5" to /proc/self/clear_refs), so
// PeakRssBytes() then reports the peak of what follows.
inline void ResetPeakRss() {
  std::ofstream clear_refs("/proc/self/clear_refs");
  clear_refs << "5";
}

// Peak resident set size (VmHWM) in bytes.
inline double PeakRssBytes() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmHWM:") {
      double kilobytes = 0;
      status >> kilobytes;
      return kilobytes * 1024.0;
    }
    std::getline(status, key);
  }
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) * 1024.0;
}

// CPU seconds of this process so far, all threads, user + system (getrusage): on a shared
// machine a fairer measure of work than wall time.
inline double ProcessCpuSeconds() {
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// The CMU takes: $MOTIF_MOCAP_DIR, else ../shared/data/mocap beside the source tree; "" if absent.
inline std::string MocapDir() {
  const char* from_env = std::getenv("MOTIF_MOCAP_DIR");
  std::string dir = from_env && *from_env ? from_env : MOTIF_DEFAULT_MOCAP_DIR;
  std::error_code error;
  return std::filesystem::is_directory(dir + "/bvh", error) ? dir : "";
}

}  // namespace motif::bench
