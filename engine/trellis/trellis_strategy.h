// The trellis stage's two ways of making an archive's trellis, behind one interface
// (engine/pipeline/mine_pipeline.h runs whichever the run's plan names):
//   * FullTrellisBuild: every column searched (BuildTrellis, trellis_builder.h): reused when a
//     finished trellis has the same parameters, resumed when one was interrupted;
//   * IncrementalTrellisUpdate: the trellis of an archive that grew by appended clips, from the
//     trellis of its earlier version and that version's search cache (UpdateTrellis,
//     trellis_update.h), the new columns searched with the recorded ε and LSH family.
// Both take the same resolved TrellisOptions (engine/pipeline/stage_options.h) and share the
// features, the neighbour rules and the search (trellis_search.h); both may leave a search cache
// for the next update, and hand each block of columns to a sink as it is written (the grower
// streams through them instead of reading the file again).
// Thread-safety: a strategy is a value; Run may be called from one thread at a time per file.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/distance/neighbour_search.h"
#include "engine/trellis/trellis_builder.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

// Every block of the trellis, in column order, as it is written; an error stops the stage.
using TrellisBlockSink = std::function<Status(uint64_t first_column,
                                              const std::vector<std::vector<Neighbour>>& columns)>;

struct TrellisStageInput {
  const FrameFileReader* archive = nullptr;  // the run's version of the archive
  std::string trellis_path;                  // written (or reused, or resumed)
  TrellisOptions options;                    // resolved; callbacks, ranks, cache path set
  // Optional. The update gives it every block it writes, in order (an update that resumes an
  // interrupted one gives only the blocks written after the resume point); the build gives it
  // none: the grower then reads the finished file.
  TrellisBlockSink on_block;
};

class TrellisStrategy {
 public:
  virtual ~TrellisStrategy() = default;
  // "build" or "update", as the reindex manifest records it.
  virtual const char* name() const = 0;
  // The trellis at input.trellis_path. The errors of the archive, the search, the old trellis
  // (Corruption) and the writer (IOError, ResourceExhausted, Busy) pass through.
  virtual Result<TrellisReport> Run(const TrellisStageInput& input) const = 0;
};

class FullTrellisBuild final : public TrellisStrategy {
 public:
  const char* name() const override { return "build"; }
  Result<TrellisReport> Run(const TrellisStageInput& input) const override;
};

class IncrementalTrellisUpdate final : public TrellisStrategy {
 public:
  // `previous_trellis`: the earlier version's trellis, over the archive's first frames;
  // `previous_cache`: its search cache (missing or stale: the features are decoded and the
  // LSH tables built again, with a note).
  IncrementalTrellisUpdate(std::string previous_trellis, std::string previous_cache)
      : previous_trellis_(std::move(previous_trellis)),
        previous_cache_(std::move(previous_cache)) {}
  const char* name() const override { return "update"; }
  // input.options must hold the recorded ε (> 0), exclusion and LSH family (resolved); the
  // update checks them against the previous trellis (InvalidArgument if they differ).
  Result<TrellisReport> Run(const TrellisStageInput& input) const override;

 private:
  std::string previous_trellis_;
  std::string previous_cache_;
};

}  // namespace motif
