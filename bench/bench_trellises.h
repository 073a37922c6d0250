// Synthetic trellis files shared by the benchmarks of the grower and of the trellis spill:
// random walks shaped like real trellises. Planted paths (runs of 8 consecutive frames around a
// walker that advances 0 to 2 frames a column and lives 100 to 500 columns) make up half of each
// column, uniform random noise nodes the rest; about K nodes a column, sorted by frame.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "engine/distance/neighbour_search.h"

namespace motif::bench {

// One walker: a planted path through the trellis.
struct Walker {
  uint64_t frame = 0;
  uint64_t columns_left = 0;
};

// The columns of a synthetic trellis of `frame_count` columns, block after block (sequential:
// the walkers carry over). Distances are 0.5 (the grower never decodes them).
class RandomWalkTrellis {
 public:
  RandomWalkTrellis(uint64_t frame_count, uint32_t k);

  // Columns [first_column, first_column + count) into *block (its vectors are reused).
  void NextBlock(uint64_t first_column, uint64_t count, std::vector<std::vector<Neighbour>>* block);

 private:
  static constexpr uint32_t kRun = 8;

  void Respawn(Walker* walker);

  uint64_t frame_count_;
  uint32_t k_;
  std::mt19937_64 rng_;
  std::vector<Walker> walkers_;
  std::vector<uint32_t> frames_;
  std::vector<uint32_t> merged_;
};

}  // namespace motif::bench
