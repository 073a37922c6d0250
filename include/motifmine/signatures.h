// Motion words and signatures (Aristidou et al. 2018; docs/design/signatures.md) through the
// public API: build them as `motifmine words` does, read every take's signature, and search the
// archive for the motions most like a clip range, as `motifmine search` does. Part of the public
// API (<motifmine/motifmine.h>); no third-party type.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "motifmine/export.h"
#include "motifmine/status.h"

namespace motifmine {

struct WordsOptions {
  MOTIFMINE_API WordsOptions();
  uint32_t motifs;  // k of the word motifs (k-means)
  uint64_t seed;    // every random choice
  int threads;      // 0: all cores
  // (stage, done, total) as the run goes.
  std::function<void(const std::string& stage, uint64_t done, uint64_t total)> progress;
};

struct WordsResult {
  uint64_t takes = 0;  // clips with at least one word
  uint64_t words = 0;
  uint32_t motifs = 0;
  std::string embedding_path;  // ARCHIVE without .mfs + .mwe, .mwm, .mws
  std::string motifs_path;
  std::string signatures_path;
};

// The motion words of the archive at `archive_path`, their embedding, motifs and every take's
// signature, written beside it (reused when up to date), as `motifmine words` does.
MOTIFMINE_API Status BuildWords(const std::string& archive_path, const WordsOptions& options,
                                WordsResult* result);

// Every clip's TF-IDF signature over the word motifs: `values` holds clips x motifs numbers,
// row by row, in archive clip order (a clip with no word has a row of zeros).
struct Signatures {
  std::vector<std::string> clips;
  uint32_t motifs = 0;
  std::vector<double> values;
};

// Reads the signatures BuildWords wrote for the archive. NotFound when there are none yet.
MOTIFMINE_API Status LoadSignatures(const std::string& archive_path, Signatures* signatures);

struct SearchMatch {
  std::string clip;
  uint64_t start = 0;  // the matching window's frames within the clip, end exclusive
  uint64_t end = 0;
  double distance = 0;  // Earth Mover's Distance between the window's and the query's signature
};

// The `top` windows most like frames [start, end) of `clip`, best first, as `motifmine search
// --clip --start --end` finds them: several a take, none sharing a frame with another of its take
// or with the query itself; a range shorter than one word padded to the word centred on it.
MOTIFMINE_API Status SearchClipRange(const std::string& archive_path, const std::string& clip,
                                     uint64_t start, uint64_t end, uint32_t top,
                                     std::vector<SearchMatch>* matches);

}  // namespace motifmine
