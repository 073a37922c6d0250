// trellis_file_measure: the figures behind the spec's "Choice of the encoding" section. Not a test
// (not run by ctest): a program that builds trellises, encodes them, and prints bytes per
// neighbour for the chosen encoding and the alternatives measured against it, and encode /
// decode speeds (one thread, best of --repeat runs, data in memory: no disk I/O in the codec
// figures; the file figures add the writer's fsync per block and the reader's mapping).
//
//   trellis_file_measure [--columns N] [--bvh DIR [--cache FILE]] [--block-columns B]
//                        [--level L] [--repeat R] [--variants]
//
// Data sets: "runs" models a trellis (neighbours in runs of 3 to 30 consecutive frames at
// random places, 100 to 500 a column, distances rising from a random floor towards eps across a
// run); "real" (with --bvh, e.g. ../shared/data/mocap/bvh) is the exact eps-trellis of the CMU
// takes: 12 weighted joints, D = sum_k w_k sqrt(2 - 2 |q_k . p_k|) (sign-aware quaternion
// distance), eps = mu - 2 sigma of 200,000 sampled pairs, a 30-frame exclusion radius inside a
// clip, the 1000 nearest kept. It takes a minute or two on two cores; --cache FILE keeps it
// (raw: u64 columns, f32 eps, then per column u32 count and count x (u32 frame, f32 distance)).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <zstd.h>

#include "formats/import/take_importer.h"
#include "formats/motion/pose_frames.h"
#include "formats/trellis_file/trellis_block_codec.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "formats/trellis_file/trellis_file_writer.h"
#include "tests/formats/trellis_file/trellis_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

// A measuring program: a failure ends the run with its status, never with figures after it.
void CheckOk(const Status& status) {
  if (status.ok()) return;
  std::fprintf(stderr, "trellis_file_measure: %s\n", status.ToString().c_str());
  std::exit(1);
}

struct DataSet {
  std::string name;
  float eps = 1.0f;
  TrellisColumns columns;
  uint64_t entries = 0;
};

double Seconds(const std::function<void()>& work, int repeat) {
  double best = 1e30;
  for (int run = 0; run < repeat; ++run) {
    const auto start = std::chrono::steady_clock::now();
    work();
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

// The exact eps-trellis of the BVH takes under `dir` (see the file comment).
bool RealTrellis(const std::string& dir, DataSet* data) {
  ImportOptions options;
  auto sources = DiscoverTakes({dir}, options);
  if (!sources.ok()) {
    std::fprintf(stderr, "%s\n", sources.status().ToString().c_str());
    return false;
  }
  std::vector<float> features;  // 4 floats per weighted joint per frame
  std::vector<uint32_t> clip_of_frame;
  std::vector<size_t> joints;
  std::vector<float> weights;
  uint32_t clip_idx = 0;
  for (const TakeSource& source : *sources) {
    if (source.format != TakeFormat::kBvh) continue;
    auto take = ImportTake(source, options);
    if (!take.ok()) {
      std::fprintf(stderr, "%s\n", take.status().ToString().c_str());
      return false;
    }
    if (joints.empty()) {
      for (size_t joint_idx = 0; joint_idx < take->joint_count(); ++joint_idx) {
        if (take->skeleton.joint(joint_idx).weight > 0) {
          joints.push_back(joint_idx);
          weights.push_back(take->skeleton.joint(joint_idx).weight);
        }
      }
    }
    const ClipFrames clip = TakeToClipFrames(*take);
    const size_t stride = FrameLayout{static_cast<uint32_t>(take->joint_count())}.stride();
    for (size_t frame_idx = 0; frame_idx < clip.info.frame_count; ++frame_idx) {
      for (size_t joint_idx : joints) {
        for (size_t component = 0; component < 4; ++component) {
          features.push_back(clip.rows[frame_idx * stride + 4 * joint_idx + component]);
        }
      }
      clip_of_frame.push_back(clip_idx);
    }
    ++clip_idx;
  }
  const size_t joint_count = joints.size();
  const size_t frame_count = clip_of_frame.size();
  const auto distance = [&](size_t a, size_t b) {
    const float* p = &features[a * 4 * joint_count];
    const float* q = &features[b * 4 * joint_count];
    float sum = 0;
    for (size_t k = 0; k < joint_count; ++k) {
      const float dot = p[4 * k] * q[4 * k] + p[4 * k + 1] * q[4 * k + 1] +
                        p[4 * k + 2] * q[4 * k + 2] + p[4 * k + 3] * q[4 * k + 3];
      sum += weights[k] * std::sqrt(std::max(0.0f, 2.0f - 2.0f * std::fabs(dot)));
    }
    return sum;
  };
  std::mt19937_64 rng(1);
  double sum = 0, sum_squares = 0;
  const int samples = 200000;
  for (int sample = 0; sample < samples; ++sample) {
    const double d = distance(rng() % frame_count, rng() % frame_count);
    sum += d;
    sum_squares += d * d;
  }
  const double mu = sum / samples;
  const double sigma = std::sqrt(sum_squares / samples - mu * mu);
  data->eps = static_cast<float>(mu - 2 * sigma);
  std::printf("real: %zu frames, %zu clips, %zu weighted joints, mu %.3f sigma %.3f eps %.3f\n",
              frame_count, static_cast<size_t>(clip_idx), joint_count, mu, sigma, data->eps);
  data->columns.assign(frame_count, {});
  const auto work = [&](size_t first, size_t step) {
    std::vector<std::pair<float, uint32_t>> found;
    for (size_t t = first; t < frame_count; t += step) {
      found.clear();
      for (size_t j = 0; j < frame_count; ++j) {
        if (clip_of_frame[j] == clip_of_frame[t] && (j > t ? j - t : t - j) < 30) continue;
        const float d = distance(t, j);
        if (d <= data->eps) found.push_back({d, static_cast<uint32_t>(j)});
      }
      if (found.size() > 1000) {
        std::nth_element(found.begin(), found.begin() + 1000, found.end());
        found.resize(1000);
      }
      std::sort(found.begin(), found.end(),
                [](const auto& a, const auto& b) { return a.second < b.second; });
      for (const auto& [d, j] : found) data->columns[t].push_back({j, d});
    }
  };
  std::thread helper(work, 1, 2);
  work(0, 2);
  helper.join();
  return true;
}

// ---- Alternatives, for the comparison table: each returns raw section bytes for one block. ----

bool LoadCache(const std::string& path, DataSet* data) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return false;
  uint64_t columns = 0;
  bool ok = std::fread(&columns, 8, 1, file) == 1 && std::fread(&data->eps, 4, 1, file) == 1;
  data->columns.assign(ok ? columns : 0, {});
  for (auto& column : data->columns) {
    uint32_t count = 0;
    ok = ok && std::fread(&count, 4, 1, file) == 1;
    column.resize(ok ? count : 0);
    for (Neighbour& neighbour : column) {
      ok = ok && std::fread(&neighbour.frame, 4, 1, file) == 1 &&
           std::fread(&neighbour.distance, 4, 1, file) == 1;
    }
  }
  std::fclose(file);
  return ok;
}

void SaveCache(const std::string& path, const DataSet& data) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) return;
  const uint64_t columns = data.columns.size();
  std::fwrite(&columns, 8, 1, file);
  std::fwrite(&data.eps, 4, 1, file);
  for (const auto& column : data.columns) {
    const uint32_t count = static_cast<uint32_t>(column.size());
    std::fwrite(&count, 4, 1, file);
    for (const Neighbour& neighbour : column) {
      std::fwrite(&neighbour.frame, 4, 1, file);
      std::fwrite(&neighbour.distance, 4, 1, file);
    }
  }
  std::fclose(file);
}

void PutVarint(std::string* out, uint64_t value) {
  while (value >= 0x80) {
    out->push_back(static_cast<char>(value | 0x80));
    value >>= 7;
  }
  out->push_back(static_cast<char>(value));
}
uint64_t ZigZag(int64_t value) {
  return (static_cast<uint64_t>(value) << 1) ^ static_cast<uint64_t>(value >> 63);
}
uint16_t ZigZag16(int32_t residual) {
  const uint16_t r = static_cast<uint16_t>(residual);
  return static_cast<uint16_t>((r << 1) ^ (0u - (r >> 15)));
}

size_t Compressed(const std::string& raw, int level) {
  std::string out(ZSTD_compressBound(raw.size()), '\0');
  return ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), level);
}

// Id encodings. 0: count + gaps as varints, first vs the column index. 1: the same, first vs the
// previous column's first + 1. 2: count + u32 gaps, byte-shuffled. 3: runs (the chosen one).
std::string EncodeIds(int variant, uint64_t first_column, const TrellisColumns& columns) {
  std::string out;
  std::vector<uint32_t> words;
  uint64_t reference = first_column;
  for (size_t column_idx = 0; column_idx < columns.size(); ++column_idx) {
    const auto& column = columns[column_idx];
    const uint64_t own = first_column + column_idx;
    if (variant == 2) {
      words.push_back(static_cast<uint32_t>(column.size()));
      for (size_t entry_idx = 0; entry_idx < column.size(); ++entry_idx) {
        words.push_back(entry_idx == 0 ? column[0].frame
                                       : column[entry_idx].frame - column[entry_idx - 1].frame - 1);
      }
      continue;
    }
    if (variant <= 1) {
      PutVarint(&out, column.size());
      for (size_t entry_idx = 0; entry_idx < column.size(); ++entry_idx) {
        if (entry_idx == 0) {
          PutVarint(&out, ZigZag(static_cast<int64_t>(column[0].frame) -
                                 static_cast<int64_t>(variant == 0 ? own : reference)));
        } else {
          PutVarint(&out, column[entry_idx].frame - column[entry_idx - 1].frame - 1);
        }
      }
    }
    reference = (column.empty() ? reference : column[0].frame) + 1;
  }
  if (variant == 2) {
    for (int byte_idx = 0; byte_idx < 4; ++byte_idx) {
      for (uint32_t word : words) out.push_back(static_cast<char>(word >> (8 * byte_idx)));
    }
  }
  return out;
}

// Distance encodings over the codes q. 0: u16 little-endian. 1: u16 byte-shuffled. 2: delta
// from the previous entry of the column, zigzag, shuffled. 3: delta 2 inside runs (the chosen
// one). 4: the 2-D planar predictor left + diagonal - diagonal-left of image coding (the
// diagonal neighbour is entry j - 1 of column t - 1). 5: LOCO-I's median edge detector over the
// same three neighbours. Residual statistics of variants 2 to 5 go to *stats.
struct ResidualStats {
  double absolute_sum = 0;
  std::vector<uint64_t> histogram = std::vector<uint64_t>(65536, 0);
};

std::string EncodeDistances(int variant, const TrellisColumns& columns, float eps,
                            ResidualStats* stats) {
  std::vector<uint16_t> words;
  std::vector<uint16_t> previous_codes;
  const TrellisColumns::value_type* previous_column = nullptr;
  for (const auto& column : columns) {
    std::vector<uint16_t> codes(column.size());
    for (size_t entry_idx = 0; entry_idx < column.size(); ++entry_idx) {
      codes[entry_idx] = trellis_file::QuantizeDistance(column[entry_idx].distance, eps);
    }
    size_t diagonal_idx = 0;
    for (size_t entry_idx = 0; entry_idx < column.size(); ++entry_idx) {
      const int code = codes[entry_idx];
      const int left = entry_idx > 0 ? codes[entry_idx - 1] : 0;
      const bool in_run =
          entry_idx > 0 && column[entry_idx].frame == column[entry_idx - 1].frame + 1;
      const bool in_run2 =
          in_run && entry_idx > 1 && column[entry_idx - 1].frame == column[entry_idx - 2].frame + 1;
      switch (variant) {
        case 0:
        case 1:
          words.push_back(static_cast<uint16_t>(code));
          break;
        case 2:
          words.push_back(ZigZag16(code - left));
          break;
        case 3: {
          const int prediction = in_run2 ? 2 * left - codes[entry_idx - 2] : left;
          words.push_back(ZigZag16(code - prediction));
          break;
        }
        case 4:
        case 5: {
          int diagonal = -1, diagonal_left = -1;
          if (previous_column != nullptr) {
            while (diagonal_idx < previous_column->size() &&
                   (*previous_column)[diagonal_idx].frame + 1 < column[entry_idx].frame) {
              ++diagonal_idx;
            }
            if (diagonal_idx < previous_column->size() &&
                (*previous_column)[diagonal_idx].frame + 1 == column[entry_idx].frame) {
              diagonal = previous_codes[diagonal_idx];
              if (diagonal_idx > 0 &&
                  (*previous_column)[diagonal_idx - 1].frame + 2 == column[entry_idx].frame) {
                diagonal_left = previous_codes[diagonal_idx - 1];
              }
            }
          }
          int prediction = left;
          if (in_run && diagonal >= 0 && diagonal_left >= 0) {
            prediction = std::clamp(left + diagonal - diagonal_left, 0, 65535);
            if (variant == 5) {
              const int low = std::min(left, diagonal), high = std::max(left, diagonal);
              prediction = diagonal_left >= high  ? low
                           : diagonal_left <= low ? high
                                                  : left + diagonal - diagonal_left;
            }
          } else if (diagonal >= 0) {
            prediction = diagonal;
          }
          words.push_back(ZigZag16(code - prediction));
          break;
        }
      }
    }
    previous_codes = std::move(codes);
    previous_column = &column;
  }
  if (variant >= 2) {
    for (uint16_t word : words) {
      stats->absolute_sum += (word >> 1) + (word & 1);  // |unzigzag(word)|
      ++stats->histogram[word];
    }
  }
  std::string out;
  if (variant == 0) {
    for (uint16_t word : words) {
      out.push_back(static_cast<char>(word));
      out.push_back(static_cast<char>(word >> 8));
    }
  } else {
    for (uint16_t word : words) out.push_back(static_cast<char>(word));
    for (uint16_t word : words) out.push_back(static_cast<char>(word >> 8));
  }
  return out;
}

void PrintVariants(const DataSet& data, uint32_t block_columns, int level) {
  const char* id_names[] = {"gaps as varints, first vs the column index",
                            "gaps as varints, first vs the previous column's first + 1",
                            "count + gaps as u32, byte shuffle"};
  const char* distance_names[] = {"u16 little-endian",
                                  "u16, byte shuffle",
                                  "delta 1 in the column, zigzag, shuffle",
                                  "delta 2 inside runs, zigzag, shuffle (chosen)",
                                  "2-D planar predictor (left + diag - diag-left)",
                                  "2-D median predictor (LOCO-I)"};
  constexpr int kDistanceVariants = 6;
  uint64_t id_bytes[3] = {}, id_raw[3] = {}, distance_bytes[kDistanceVariants] = {};
  std::vector<ResidualStats> stats(kDistanceVariants);
  for (uint64_t first = 0; first < data.columns.size(); first += block_columns) {
    const TrellisColumns block =
        Slice(data.columns, first, std::min<uint64_t>(block_columns, data.columns.size() - first));
    for (int variant = 0; variant < 3; ++variant) {
      const std::string raw = EncodeIds(variant, first, block);
      id_raw[variant] += raw.size();
      id_bytes[variant] += Compressed(raw, level);
    }
    for (int variant = 0; variant < kDistanceVariants; ++variant) {
      distance_bytes[variant] +=
          Compressed(EncodeDistances(variant, block, data.eps, &stats[variant]), level);
    }
  }
  const double entries = static_cast<double>(data.entries);
  std::printf("  alternatives (zstd level %d, %u-column blocks), bytes per neighbour:\n", level,
              block_columns);
  for (int variant = 0; variant < 3; ++variant) {
    std::printf("    ids: %-58s %.4f (raw %.3f)\n", id_names[variant], id_bytes[variant] / entries,
                id_raw[variant] / entries);
  }
  for (int variant = 0; variant < kDistanceVariants; ++variant) {
    std::printf("    distances: %-52s %.4f", distance_names[variant],
                distance_bytes[variant] / entries);
    if (variant >= 2) {
      // Zero-order entropy of the 16-bit residual words: what an ideal coder of independent
      // residuals would need.
      double bits = 0;
      for (uint64_t count : stats[variant].histogram) {
        if (count > 0) bits -= count * std::log2(count / entries);
      }
      std::printf("  (mean |residual| %.0f, entropy %.4f)", stats[variant].absolute_sum / entries,
                  bits / 8 / entries);
    }
    std::printf("\n");
  }
}

void Measure(DataSet& data, uint32_t block_columns, int level, int repeat, bool variants) {
  data.entries = 0;
  uint64_t runs = 0, max_k = 0;
  for (const auto& column : data.columns) {
    data.entries += column.size();
    max_k = std::max<uint64_t>(max_k, column.size());
    for (size_t entry_idx = 0; entry_idx < column.size(); ++entry_idx) {
      if (entry_idx == 0 || column[entry_idx].frame != column[entry_idx - 1].frame + 1) ++runs;
    }
  }
  const double entries = static_cast<double>(data.entries);
  std::printf("== %s: %zu columns, %llu neighbours (mean %.1f, max %llu), mean run %.2f frames\n",
              data.name.c_str(), data.columns.size(), static_cast<unsigned long long>(data.entries),
              entries / data.columns.size(), static_cast<unsigned long long>(max_k),
              entries / std::max<uint64_t>(runs, 1));
  std::vector<TrellisColumns> blocks;
  for (uint64_t first = 0; first < data.columns.size(); first += block_columns) {
    blocks.push_back(
        Slice(data.columns, first, std::min<uint64_t>(block_columns, data.columns.size() - first)));
  }
  trellis_file::BlockEncoder encoder(level);
  std::vector<std::string> encoded(blocks.size());
  std::vector<trellis_file::BlockHandle> handles(blocks.size());
  const double encode_seconds = Seconds(
      [&] {
        for (size_t block_idx = 0; block_idx < blocks.size(); ++block_idx) {
          CheckOk(encoder.Encode(block_idx * block_columns, blocks[block_idx], data.eps,
                                 &encoded[block_idx], &handles[block_idx]));
        }
      },
      repeat);
  uint64_t block_bytes = 0, id_bytes = 0, id_raw_bytes = 0, distance_bytes = 0;
  for (const std::string& block : encoded) {
    trellis_file::BlockHeader header;
    CheckOk(trellis_file::BlockHeader::DecodeFrom(reinterpret_cast<const uint8_t*>(block.data()),
                                                  &header));
    block_bytes += block.size();
    id_bytes += header.ids_bytes;
    id_raw_bytes += header.ids_raw_bytes;
    distance_bytes += header.distances_bytes;
  }
  trellis_file::BlockDecoder decoder;
  trellis_file::BlockLimits limits;
  limits.frame_count = data.columns.size();
  limits.k_max = 1000;
  limits.eps = data.eps;
  TrellisBlock block;
  const auto decode_all = [&](bool distances) {
    for (size_t block_idx = 0; block_idx < blocks.size(); ++block_idx) {
      CheckOk(decoder.Decode(reinterpret_cast<const uint8_t*>(encoded[block_idx].data()),
                             handles[block_idx], limits, &block, distances));
    }
  };
  const double decode_seconds = Seconds([&] { decode_all(true); }, repeat);
  const double ids_seconds = Seconds([&] { decode_all(false); }, repeat);

  // Through the file: the writer (a fsync per block) and the reader (mapped, checksummed).
  TempDir dir;
  const std::string path = dir.File("measure.mtr");
  TrellisParams params = MakeParams(data.columns.size(), 1000);
  params.eps = data.eps;
  TrellisFileWriterOptions options;
  options.block_columns = block_columns;
  options.zstd_level = level;
  const double write_seconds = Seconds(
      [&] {
        std::filesystem::remove(path);
        CheckOk(WriteTrellis(path, params, data.columns, options));
      },
      1);
  auto reader = TrellisFileReader::Open(path);
  CheckOk(reader.status());
  const double read_seconds = Seconds(
      [&] {
        for (uint64_t block_idx = 0; block_idx < (*reader)->block_count(); ++block_idx) {
          CheckOk((*reader)->ReadBlock(block_idx, &block));
        }
      },
      repeat);

  std::printf(
      "  bytes per neighbour: %.4f total (ids %.4f (raw %.3f), distances %.4f, block framing"
      " %.4f); file %.4f\n",
      block_bytes / entries, id_bytes / entries, id_raw_bytes / entries, distance_bytes / entries,
      (block_bytes - id_bytes - distance_bytes) / entries, (*reader)->file_bytes() / entries);
  std::printf(
      "  codec, one thread: encode %.1f M neighbours/s, decode %.1f M/s, frames only %.1f "
      "M/s\n",
      entries / encode_seconds / 1e6, entries / decode_seconds / 1e6, entries / ids_seconds / 1e6);
  std::printf("  file: write %.1f M/s (fsync per block), ReadBlock %.1f M/s (page cache warm)\n",
              entries / write_seconds / 1e6, entries / read_seconds / 1e6);
  if (variants) PrintVariants(data, block_columns, level);
}

}  // namespace
}  // namespace motif::testing

int main(int argc, char** argv) {
  using namespace motif::testing;
  uint64_t columns = 40000;
  uint32_t block_columns = 4096;
  int level = 3, repeat = 5;
  bool variants = false;
  std::string bvh_dir, cache;
  for (int arg_idx = 1; arg_idx < argc; ++arg_idx) {
    const std::string arg = argv[arg_idx];
    const auto next = [&] { return arg_idx + 1 < argc ? std::string(argv[++arg_idx]) : ""; };
    if (arg == "--columns")
      columns = std::stoull(next());
    else if (arg == "--bvh")
      bvh_dir = next();
    else if (arg == "--cache")
      cache = next();
    else if (arg == "--block-columns")
      block_columns = static_cast<uint32_t>(std::stoul(next()));
    else if (arg == "--level")
      level = std::stoi(next());
    else if (arg == "--repeat")
      repeat = std::stoi(next());
    else if (arg == "--variants")
      variants = true;
    else {
      std::fprintf(stderr,
                   "usage: %s [--columns N] [--bvh DIR [--cache FILE]] [--block-columns B] "
                   "[--level L] [--repeat R] [--variants]\n",
                   argv[0]);
      return 2;
    }
  }
  DataSet runs;
  runs.name = "runs";
  runs.eps = 1.02f;
  runs.columns = MakeRunColumns(columns, runs.eps, 100, 500, 1);
  Measure(runs, block_columns, level, repeat, variants);
  if (!bvh_dir.empty()) {
    DataSet real;
    real.name = "real";
    if (cache.empty() || !LoadCache(cache, &real)) {
      if (!RealTrellis(bvh_dir, &real)) return 1;
      if (!cache.empty()) SaveCache(cache, real);
    }
    Measure(real, block_columns, level, repeat, variants);
  }
  return 0;
}
