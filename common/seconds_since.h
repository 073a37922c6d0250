// SecondsSince: seconds elapsed on the steady clock, for the stage timings that the builders and
// the commands report in their stats and summaries.
#pragma once

#include <chrono>

namespace motif {

inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace motif
