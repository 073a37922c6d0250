// TrellisParams: what a matching trellis was built from and with, stored in the header of its
// file (docs/formats/trellis_file.md, section 4.2; encoded by trellis_file_format.h). A leaf, so
// that the format, the writer and the reader all include it and not each other. operator==
// compares the floats by their bits (defined with the encoding, in trellis_file_format.cc).
// Thread-safety: a value type.
#pragma once

#include <cstdint>
#include <string>

namespace motif {

// What a trellis was built from and with; stored in the file. Two trellises with equal params
// over the same archive are interchangeable.
struct TrellisParams {
  uint64_t frame_count = 0;       // columns = archive frames
  uint64_t archive_identity = 0;  // identifies the archive version (FrameFileReader identity)
  float eps = 0;
  float mu = 0;  // sampled distance mean and std dev (0 if eps was given)
  float sigma = 0;
  uint32_t k_max = 0;
  uint32_t exclusion_frames = 0;
  uint32_t search_mode = 0;  // 0 exact, 1 LSH
  uint64_t seed = 0;
  uint64_t weights_hash = 0;  // hash of the per-joint weights used
  std::string search_params;  // e.g. "lsh tables=8 hashes=12 width=0.6 probes=..." (free text)

  bool operator==(const TrellisParams& other) const;
};

}  // namespace motif
