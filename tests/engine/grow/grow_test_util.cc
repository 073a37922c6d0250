#include "tests/engine/grow/grow_test_util.h"

#include <algorithm>
#include <random>
#include <set>

#include "engine/synth/motion_synthesizer.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "tests/formats/trellis_file/trellis_test_util.h"

namespace motif {
void PrintTo(const PathCandidate& c, std::ostream* out) {
  *out << "top [" << c.top_start << ", " << c.top_end << ") match [" << c.match_start << ", "
       << c.match_end << ") root (" << c.root_column << ", " << c.root_frame << ")";
}
}  // namespace motif

namespace motif::testing {

GrowColumns EmptyColumns(uint64_t frame_count) { return GrowColumns(frame_count); }

void AddNode(GrowColumns* columns, uint64_t column, uint64_t frame) {
  std::vector<Neighbour>& nodes = (*columns)[column];
  auto it = std::lower_bound(nodes.begin(), nodes.end(), frame,
                             [](const Neighbour& node, uint64_t f) { return node.frame < f; });
  if (it != nodes.end() && it->frame == frame) return;
  nodes.insert(it, Neighbour{static_cast<uint32_t>(frame), 0.5f});
}

void AddPath(GrowColumns* columns, uint64_t first_column, const std::vector<uint64_t>& frames) {
  for (size_t idx = 0; idx < frames.size(); ++idx)
    AddNode(columns, first_column + idx, frames[idx]);
}

void AddDiagonal(GrowColumns* columns, uint64_t first_column, uint64_t first_frame,
                 uint64_t length) {
  for (uint64_t idx = 0; idx < length; ++idx)
    AddNode(columns, first_column + idx, first_frame + idx);
}

Result<std::vector<PathCandidate>> GrowInMemory(const GrowColumns& columns,
                                                const std::vector<uint64_t>& clip_starts,
                                                const GrowOptions& options) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<PathGrower> grower,
                         PathGrower::Create(columns.size(), clip_starts, options));
  for (const std::vector<Neighbour>& column : columns) {
    MOTIF_RETURN_IF_ERROR(grower->AddColumn(column.data(), column.size()));
  }
  return grower->Finish();
}

Status WriteColumns(const std::string& path, const GrowColumns& columns, uint32_t block_columns) {
  size_t k_max = 1;
  for (const auto& column : columns) k_max = std::max(k_max, column.size());
  TrellisParams params = MakeParams(columns.size(), static_cast<uint32_t>(k_max));
  TrellisFileWriterOptions options;
  options.block_columns = block_columns;
  options.file_system = NoSyncFileSystem();
  return WriteTrellis(path, params, columns, options);
}

Result<std::vector<PathCandidate>> GrowThroughFile(const std::string& path,
                                                   const GrowColumns& columns,
                                                   const std::vector<uint64_t>& clip_starts,
                                                   const GrowOptions& options,
                                                   uint32_t block_columns) {
  MOTIF_RETURN_IF_ERROR(WriteColumns(path, columns, block_columns));
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> reader, TrellisFileReader::Open(path));
  return GrowPaths(*reader, clip_starts, options);
}

PathCandidate Candidate(uint64_t top_start, uint64_t top_end, uint64_t match_start,
                        uint64_t match_end) {
  return {top_start, top_end, match_start, match_end, top_start, match_start};
}

GrowColumns RandomColumns(uint64_t frame_count, uint64_t seed, int paths, int noise,
                          uint32_t max_step) {
  std::mt19937_64 rng(seed);
  GrowColumns columns(frame_count);
  auto uniform = [&](uint64_t n) { return n == 0 ? 0 : rng() % n; };
  for (int path = 0; path < paths; ++path) {
    uint64_t column = uniform(frame_count);
    uint64_t frame = uniform(frame_count);
    const uint64_t length = 1 + uniform(frame_count / 2 + 1);
    for (uint64_t step = 0; step < length && column < frame_count && frame < frame_count; ++step) {
      if (uniform(20) != 0) AddNode(&columns, column, frame);  // occasional misses
      // A run of similar frames around the path's node.
      if (uniform(4) == 0 && frame + 1 < frame_count) AddNode(&columns, column, frame + 1);
      ++column;
      frame += uniform(max_step + 1);
    }
  }
  for (uint64_t column = 0; column < frame_count; ++column) {
    const int count = static_cast<int>(uniform(static_cast<uint64_t>(noise) + 1));
    for (int idx = 0; idx < count; ++idx) AddNode(&columns, column, uniform(frame_count));
  }
  return columns;
}

std::vector<uint64_t> RandomClipStarts(uint64_t frame_count, uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::set<uint64_t> starts = {0};
  while (static_cast<int>(starts.size()) < count && starts.size() < frame_count) {
    starts.insert(rng() % frame_count);
  }
  return {starts.begin(), starts.end()};
}

Status WriteSynthArchive(const std::string& path, uint64_t frames, uint64_t seed) {
  SynthOptions options;
  options.frames = frames;
  options.motifs = 2;
  options.instances_min = 3;
  options.instances_max = 3;
  options.motif_seconds_max = 1.5;
  options.seed = seed;
  options.clip_seconds_min = 10;
  options.clip_seconds_max = 20;
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<MotionSynthesizer> synthesizer,
                         MotionSynthesizer::Create(options));
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileWriter> writer,
                         FrameFileWriter::Create(path, synthesizer->skeleton(), options.fps));
  MOTIF_RETURN_IF_ERROR(
      synthesizer->Run([&](const ClipFrames& clip) { return writer->AppendClip(clip); }));
  return writer->Commit();
}

std::string Describe(const std::vector<PathCandidate>& candidates) {
  std::string text;
  for (const PathCandidate& c : candidates) {
    text += "  top [" + std::to_string(c.top_start) + ", " + std::to_string(c.top_end) +
            ") match [" + std::to_string(c.match_start) + ", " + std::to_string(c.match_end) +
            ") root (" + std::to_string(c.root_column) + ", " + std::to_string(c.root_frame) +
            ")\n";
  }
  return text;
}

}  // namespace motif::testing
