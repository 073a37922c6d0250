#include "tests/formats/trellis_file/trellis_test_util.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "formats/trellis_file/trellis_block_codec.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif::testing {

TrellisParams MakeParams(uint64_t frame_count, uint32_t k_max) {
  TrellisParams params;
  params.frame_count = frame_count;
  params.archive_identity = 0x0123456789abcdefull;
  params.eps = 1.0f;
  params.mu = 3.0f;
  params.sigma = 1.0f;
  params.k_max = k_max;
  params.exclusion_frames = 30;
  params.search_mode = 1;
  params.seed = 42;
  params.weights_hash = 0xfedcba9876543210ull;
  params.search_params = "lsh tables=8 hashes=12 width=0.6 probes=2";
  return params;
}

TrellisColumns MakeRunColumns(uint64_t frame_count, float eps, uint32_t min_k, uint32_t max_k,
                              uint64_t seed, uint32_t min_run, uint32_t max_run) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  TrellisColumns columns(frame_count);
  for (uint64_t column_idx = 0; column_idx < frame_count; ++column_idx) {
    const uint64_t target =
        std::min<uint64_t>(frame_count, min_k + rng() % (uint64_t{max_k} - min_k + 1));
    std::map<uint32_t, float> entries;
    while (entries.size() < target) {
      const uint64_t length =
          std::min<uint64_t>(frame_count, min_run + rng() % (uint64_t{max_run} - min_run + 1));
      const uint64_t start = rng() % (frame_count - length + 1);
      const double floor_fraction = 0.9 * unit(rng);
      for (uint64_t offset = 0; offset < length && entries.size() < target; ++offset) {
        const double x = (offset + 0.5) / length * 2 - 1;  // -1 .. 1 across the run
        double fraction = std::sqrt(floor_fraction * floor_fraction +
                                    (1 - floor_fraction * floor_fraction) * x * x);
        fraction = std::clamp(fraction + (unit(rng) - 0.5) * 1e-3, 0.0, 1.0);
        entries.emplace(static_cast<uint32_t>(start + offset),
                        std::min(eps, static_cast<float>(fraction * eps)));
      }
    }
    for (const auto& [frame, distance] : entries) columns[column_idx].push_back({frame, distance});
  }
  return columns;
}

TrellisColumns Slice(const TrellisColumns& columns, uint64_t first, uint64_t count) {
  return TrellisColumns(columns.begin() + first, columns.begin() + first + count);
}

Status WriteTrellis(const std::string& path, const TrellisParams& params,
                    const TrellisColumns& columns, const TrellisFileWriterOptions& options) {
  MOTIF_ASSIGN_OR_RETURN(auto writer, TrellisFileWriter::OpenOrResume(path, params, options));
  while (writer->next_column() < params.frame_count) {
    const uint64_t count =
        std::min<uint64_t>(writer->block_columns(), params.frame_count - writer->next_column());
    MOTIF_RETURN_IF_ERROR(writer->AppendBlock(Slice(columns, writer->next_column(), count)));
  }
  return writer->Finish();
}

Result<TrellisColumns> ReadTrellis(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(auto reader, TrellisFileReader::Open(path));
  TrellisColumns columns;
  MOTIF_RETURN_IF_ERROR(reader->ReadColumns(0, reader->column_count(), &columns));
  return columns;
}

void ExpectSameWithinBound(const TrellisColumns& written, const TrellisColumns& read, float eps) {
  ASSERT_EQ(written.size(), read.size());
  const double bound = trellis_file::QuantizationBound(eps);
  for (size_t column_idx = 0; column_idx < written.size(); ++column_idx) {
    ASSERT_EQ(written[column_idx].size(), read[column_idx].size()) << "column " << column_idx;
    for (size_t entry_idx = 0; entry_idx < written[column_idx].size(); ++entry_idx) {
      const Neighbour& expected = written[column_idx][entry_idx];
      const Neighbour& actual = read[column_idx][entry_idx];
      ASSERT_EQ(expected.frame, actual.frame) << "column " << column_idx << " entry " << entry_idx;
      ASSERT_LE(std::fabs(static_cast<double>(expected.distance) - actual.distance), bound)
          << "column " << column_idx << " entry " << entry_idx;
      ASSERT_GE(actual.distance, 0.0f);
      ASSERT_LE(actual.distance, eps);
    }
  }
}

int64_t MappedResidentBytes(const std::string& path) {
  std::ifstream smaps("/proc/self/smaps");
  if (!smaps) return -1;
  std::error_code error;
  const std::string canonical = std::filesystem::canonical(path, error).string();
  int64_t resident_bytes = 0;
  bool in_mapping = false;
  std::string line;
  // A mapping's header line ends with its path; its "Rss:" line follows in kB.
  while (std::getline(smaps, line)) {
    if (line.rfind("Rss:", 0) == 0) {
      if (in_mapping) resident_bytes += std::stoll(line.substr(4)) * 1024;
    } else if (!line.empty() && std::isxdigit(static_cast<unsigned char>(line[0])) &&
               line.find('-') != std::string::npos && line.find(':') > line.find(' ')) {
      in_mapping = line.size() >= canonical.size() &&
                   line.compare(line.size() - canonical.size(), canonical.size(), canonical) == 0;
    }
  }
  return resident_bytes;
}

}  // namespace motif::testing
