#include "tests/engine/cluster/cluster_test_util.h"

#include <algorithm>

#include "formats/trellis_file/trellis_file_writer.h"

namespace motif::testing {

Columns MakePlantedColumns(uint64_t frames, const std::vector<PlantedMotif>& motifs, uint32_t noise,
                           uint64_t seed) {
  Columns columns(frames);
  for (const PlantedMotif& motif : motifs) {
    for (size_t i = 0; i < motif.starts.size(); ++i) {
      for (uint64_t k = 0; k < motif.length; ++k) {
        std::vector<Neighbour>& column = columns[motif.starts[i] + k];
        for (size_t j = 0; j < motif.starts.size(); ++j) {
          if (j == i) continue;
          for (int64_t delta = -1; delta <= 1; ++delta) {
            const int64_t offset = static_cast<int64_t>(k) + delta;
            if (offset < 0 || offset >= static_cast<int64_t>(motif.length)) continue;
            column.push_back(
                {static_cast<uint32_t>(motif.starts[j] + static_cast<uint64_t>(offset)),
                 delta == 0 ? 0.25f : 0.5f});
          }
        }
      }
    }
  }
  uint64_t state = seed;
  auto next = [&state] {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  };
  for (uint64_t column = 0; column < frames; ++column) {
    for (uint32_t idx = 0; idx < noise; ++idx) {
      columns[column].push_back({static_cast<uint32_t>(next() % frames), 0.9f});
    }
    std::vector<Neighbour>& list = columns[column];
    std::sort(list.begin(), list.end(), [](const Neighbour& a, const Neighbour& b) {
      return a.frame != b.frame ? a.frame < b.frame : a.distance < b.distance;
    });
    list.erase(
        std::unique(list.begin(), list.end(),
                    [](const Neighbour& a, const Neighbour& b) { return a.frame == b.frame; }),
        list.end());
  }
  return columns;
}

std::vector<PathCandidate> MakePlantedCandidates(const std::vector<PlantedMotif>& motifs) {
  std::vector<PathCandidate> candidates;
  for (const PlantedMotif& motif : motifs) {
    for (uint64_t top : motif.starts) {
      for (uint64_t match : motif.starts) {
        if (top == match) continue;
        PathCandidate full{top, top + motif.length, match, match + motif.length, top, match};
        PathCandidate branch = full;
        branch.top_end = top + motif.length / 2;
        branch.match_end = match + motif.length / 2;
        candidates.push_back(branch);
        candidates.push_back(full);
      }
    }
  }
  return candidates;
}

Status WriteColumns(const std::string& path, const Columns& columns, uint32_t block_columns) {
  TrellisParams params;
  params.frame_count = columns.size();
  params.archive_identity = 7;
  params.eps = 1.0f;
  params.k_max = 1;
  for (const auto& column : columns) {
    params.k_max = std::max<uint32_t>(params.k_max, static_cast<uint32_t>(column.size()));
  }
  params.search_params = "test";
  TrellisFileWriterOptions options;
  options.block_columns = block_columns;
  MOTIF_ASSIGN_OR_RETURN(auto writer, TrellisFileWriter::OpenOrResume(path, params, options));
  for (uint64_t first = 0; first < columns.size(); first += block_columns) {
    const uint64_t end = std::min<uint64_t>(first + block_columns, columns.size());
    Columns block(columns.begin() + static_cast<ptrdiff_t>(first),
                  columns.begin() + static_cast<ptrdiff_t>(end));
    MOTIF_RETURN_IF_ERROR(writer->AppendBlock(block));
  }
  return writer->Finish();
}

}  // namespace motif::testing
