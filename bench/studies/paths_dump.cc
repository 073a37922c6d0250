// Study: prints the candidate paths of a paths file, one per line:
// top_start top_end match_start match_end (global frames, end exclusive).
//
//   paths_dump PATHS.mpa
#include <cstdio>
#include <iostream>

#include "formats/paths_file/paths_file_reader.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: paths_dump PATHS.mpa\n";
    return 2;
  }
  auto reader = motif::PathsFileReader::Open(argv[1]);
  if (!reader.ok()) {
    std::cerr << reader.status().ToString() << "\n";
    return 1;
  }
  for (const motif::PathCandidate& path : (*reader)->candidates()) {
    std::printf("%llu %llu %llu %llu\n", static_cast<unsigned long long>(path.top_start),
                static_cast<unsigned long long>(path.top_end),
                static_cast<unsigned long long>(path.match_start),
                static_cast<unsigned long long>(path.match_end));
  }
  return 0;
}
