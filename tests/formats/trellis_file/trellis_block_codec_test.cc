// The block codec alone (formats/trellis_file/trellis_block_codec.h): round trips of awkward
// columns, the quantisation bound, canonical bytes, compression on trellis-shaped data, and
// decoding of damaged or random bytes (never a crash, always Corruption).
#include "formats/trellis_file/trellis_block_codec.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "tests/formats/trellis_file/trellis_test_util.h"

namespace motif::testing {
namespace {

using trellis_file::BlockDecoder;
using trellis_file::BlockEncoder;
using trellis_file::BlockHandle;
using trellis_file::BlockLimits;

struct Encoded {
  std::string bytes;
  BlockHandle handle;
};

Encoded EncodeBlock(uint64_t first_column, const TrellisColumns& columns, float eps,
                    int level = 3) {
  BlockEncoder encoder(level);
  Encoded encoded;
  EXPECT_TRUE(encoder.Encode(first_column, columns, eps, &encoded.bytes, &encoded.handle).ok());
  return encoded;
}

BlockLimits Limits(uint64_t frame_count, uint32_t k_max, float eps) {
  BlockLimits limits;
  limits.frame_count = frame_count;
  limits.k_max = k_max;
  limits.eps = eps;
  return limits;
}

Status Decode(const Encoded& encoded, const BlockLimits& limits, TrellisBlock* block) {
  BlockDecoder decoder;
  return decoder.Decode(reinterpret_cast<const uint8_t*>(encoded.bytes.data()), encoded.handle,
                        limits, block);
}

TrellisColumns Columns(const TrellisBlock& block) {
  TrellisColumns columns(block.column_count);
  for (uint32_t column_idx = 0; column_idx < block.column_count; ++column_idx) {
    columns[column_idx].assign(block.neighbours.begin() + block.offsets[column_idx],
                               block.neighbours.begin() + block.offsets[column_idx + 1]);
  }
  return columns;
}

void ExpectRoundTrip(uint64_t first_column, const TrellisColumns& columns, float eps,
                     uint64_t frame_count, uint32_t k_max) {
  const Encoded encoded = EncodeBlock(first_column, columns, eps);
  TrellisBlock block;
  const Status status = Decode(encoded, Limits(frame_count, k_max, eps), &block);
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(block.first_column, first_column);
  EXPECT_EQ(block.column_count, columns.size());
  ExpectSameWithinBound(columns, Columns(block), eps);
}

TEST(TrellisBlockCodec, QuantisationErrorStaysWithinTheStatedBound) {
  std::mt19937_64 rng(7);
  for (float eps : {1.0f, 1.02f, 0.3f, 1e-3f, 250.0f}) {
    const double bound = trellis_file::QuantizationBound(eps);
    EXPECT_LT(bound, eps / 131070.0 * 1.01);
    std::uniform_real_distribution<float> distance(0.0f, eps);
    double worst = 0;
    for (int sample = 0; sample < 200000; ++sample) {
      const float written = std::min(eps, distance(rng));
      const float decoded =
          trellis_file::DequantizeDistance(trellis_file::QuantizeDistance(written, eps), eps);
      worst = std::max(worst, std::fabs(static_cast<double>(decoded) - written));
      ASSERT_LE(decoded, eps);
      ASSERT_GE(decoded, 0.0f);
    }
    EXPECT_LE(worst, bound) << "eps " << eps;
    EXPECT_GT(worst, 0.9 * eps / 131070.0) << "the bound is not tight: eps " << eps;
  }
}

TEST(TrellisBlockCodec, DistancesZeroAndEpsAreExact) {
  for (float eps : {1.0f, 1.02f, 0.123456f, 3e-5f, 1e6f}) {
    EXPECT_EQ(trellis_file::QuantizeDistance(0.0f, eps), 0);
    EXPECT_EQ(trellis_file::QuantizeDistance(eps, eps), 65535);
    EXPECT_EQ(trellis_file::DequantizeDistance(0, eps), 0.0f);
    EXPECT_EQ(trellis_file::DequantizeDistance(65535, eps), eps) << "eps " << eps;
  }
}

TEST(TrellisBlockCodec, QuantisationIsMonotone) {
  const float eps = 1.02f;
  for (uint32_t code = 1; code < 65536; ++code) {
    ASSERT_LT(trellis_file::DequantizeDistance(static_cast<uint16_t>(code - 1), eps),
              trellis_file::DequantizeDistance(static_cast<uint16_t>(code), eps));
  }
}

TEST(TrellisBlockCodec, RoundTripsEmptyColumns) {
  ExpectRoundTrip(0, TrellisColumns(17), 1.0f, 17, 5);
  TrellisColumns mixed(9);
  mixed[3] = {{1, 0.5f}, {2, 0.25f}};
  mixed[8] = {{0, 1.0f}};
  ExpectRoundTrip(100, mixed, 1.0f, 200, 5);
}

TEST(TrellisBlockCodec, RoundTripsColumnsOfOneNeighbour) {
  TrellisColumns columns;
  for (uint32_t column_idx = 0; column_idx < 50; ++column_idx) {
    columns.push_back({{(column_idx * 7919u) % 1000u, 0.01f * (column_idx % 100)}});
  }
  ExpectRoundTrip(950, columns, 1.0f, 1000, 1);
}

TEST(TrellisBlockCodec, RoundTripsColumnsOfAThousandNeighbours) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> distance(0.0f, 1.02f);
  TrellisColumns columns(20);
  for (size_t column_idx = 0; column_idx < columns.size(); ++column_idx) {
    // Alternate dense runs and scattered frames.
    std::vector<uint32_t> frames;
    if (column_idx % 2 == 0) {
      for (uint32_t frame = 0; frame < 1000; ++frame) frames.push_back(5000 + frame);
    } else {
      uint32_t frame = 0;
      for (int entry_idx = 0; entry_idx < 1000; ++entry_idx) {
        frame += 1 + static_cast<uint32_t>(rng() % 90);
        frames.push_back(frame);
      }
    }
    for (uint32_t frame : frames) columns[column_idx].push_back({frame, distance(rng)});
  }
  ExpectRoundTrip(0, columns, 1.02f, 100000, 1000);
}

TEST(TrellisBlockCodec, RoundTripsFramesNearTheTopOfTheU32Range) {
  const uint64_t frame_count = 1ull << 32;
  const uint64_t first_column = frame_count - 4;
  TrellisColumns columns(4);
  columns[0] = {{0, 0.5f}, {1, 0.5f}, {0xFFFFFFFEu, 0.25f}, {0xFFFFFFFFu, 0.0f}};
  columns[1] = {{0xFFFFFFFFu, 1.0f}};
  columns[2] = {{0x7FFFFFFFu, 0.75f}, {0x80000000u, 0.5f}, {0xFFFFFFF0u, 0.1f}};
  columns[3] = {{0, 0.3f}, {0xFFFFFFFFu, 0.2f}};
  ExpectRoundTrip(first_column, columns, 1.0f, frame_count, 4);
  // A column far below its own index and one far above it.
  TrellisColumns far(2);
  far[0] = {{0xFFFFFFFFu, 0.5f}};
  far[1] = {{0, 0.5f}};
  ExpectRoundTrip(0, far, 1.0f, frame_count, 1);
}

TEST(TrellisBlockCodec, RoundTripsTrellisShapedColumns) {
  const TrellisColumns columns = MakeRunColumns(2000, 1.02f, 100, 500, 11);
  ExpectRoundTrip(0, columns, 1.02f, 2000, 1000);
}

TEST(TrellisBlockCodec, DecodingWithoutDistancesGivesTheFramesAndZeroDistances) {
  const TrellisColumns columns = MakeRunColumns(300, 1.0f, 10, 50, 5);
  const Encoded encoded = EncodeBlock(0, columns, 1.0f);
  BlockDecoder decoder;
  TrellisBlock block;
  ASSERT_TRUE(decoder
                  .Decode(reinterpret_cast<const uint8_t*>(encoded.bytes.data()), encoded.handle,
                          Limits(300, 1000, 1.0f), &block, /*decode_distances=*/false)
                  .ok());
  const TrellisColumns decoded = Columns(block);
  for (size_t column_idx = 0; column_idx < columns.size(); ++column_idx) {
    ASSERT_EQ(decoded[column_idx].size(), columns[column_idx].size());
    for (size_t entry_idx = 0; entry_idx < columns[column_idx].size(); ++entry_idx) {
      EXPECT_EQ(decoded[column_idx][entry_idx].frame, columns[column_idx][entry_idx].frame);
      EXPECT_EQ(decoded[column_idx][entry_idx].distance, 0.0f);
    }
  }
}

// The encoding is canonical: decoding and encoding again gives the same bytes, so a resumed
// build and an uninterrupted one cannot differ by the path their values took.
TEST(TrellisBlockCodec, EncodingDecodedColumnsGivesTheSameBytes) {
  const TrellisColumns columns = MakeRunColumns(500, 1.02f, 20, 200, 9);
  const Encoded encoded = EncodeBlock(1000, columns, 1.02f);
  TrellisBlock block;
  ASSERT_TRUE(Decode(encoded, Limits(5000, 1000, 1.02f), &block).ok());
  EXPECT_EQ(EncodeBlock(1000, Columns(block), 1.02f).bytes, encoded.bytes);
}

// Trellis-shaped data (the model of docs/formats/trellis_file.md: runs of 3 to 30 frames, 100 to
// 500 neighbours) must stay well under 2 bytes a neighbour; the spec's table has the figures.
TEST(TrellisBlockCodec, CompressesTrellisShapedColumnsBelowTwoBytesPerNeighbour) {
  const uint64_t frame_count = 8192;
  const TrellisColumns columns = MakeRunColumns(frame_count, 1.02f, 100, 500, 21);
  uint64_t bytes = 0, entries = 0;
  for (uint64_t first = 0; first < frame_count; first += 4096) {
    bytes += EncodeBlock(first, Slice(columns, first, 4096), 1.02f).bytes.size();
  }
  for (const auto& column : columns) entries += column.size();
  const double per_entry = static_cast<double>(bytes) / static_cast<double>(entries);
  EXPECT_LT(per_entry, 1.75);
  std::printf("%.4f bytes per neighbour over %llu neighbours\n", per_entry,
              static_cast<unsigned long long>(entries));
}

TEST(TrellisBlockCodec, RejectsEveryFlippedByteWithCorruption) {
  const TrellisColumns columns = MakeRunColumns(40, 1.0f, 2, 8, 13, 1, 4);
  const Encoded encoded = EncodeBlock(0, columns, 1.0f);
  for (size_t byte_idx = 0; byte_idx < encoded.bytes.size(); ++byte_idx) {
    Encoded damaged = encoded;
    damaged.bytes[byte_idx] = static_cast<char>(damaged.bytes[byte_idx] ^ 0x20);
    TrellisBlock block;
    const Status status = Decode(damaged, Limits(40, 1000, 1.0f), &block);
    ASSERT_TRUE(status.IsCorruption()) << "byte " << byte_idx << ": " << status.ToString();
  }
}

TEST(TrellisBlockCodec, RejectsABlockThatDisagreesWithItsIndexEntry) {
  const TrellisColumns columns = MakeRunColumns(40, 1.0f, 2, 8, 13);
  const Encoded encoded = EncodeBlock(0, columns, 1.0f);
  TrellisBlock block;
  for (int field = 0; field < 4; ++field) {
    Encoded wrong = encoded;
    if (field == 0) wrong.handle.first_column = 8;
    if (field == 1) wrong.handle.column_count = 39;
    if (field == 2) wrong.handle.neighbour_count += 1;
    if (field == 3) wrong.handle.checksum ^= 1;
    EXPECT_TRUE(Decode(wrong, Limits(40, 1000, 1.0f), &block).IsCorruption()) << field;
  }
  // Frames beyond the archive, columns longer than k_max.
  EXPECT_TRUE(Decode(encoded, Limits(20, 1000, 1.0f), &block).IsCorruption());
  EXPECT_TRUE(Decode(encoded, Limits(40, 3, 1.0f), &block).IsCorruption());
}

// Valid checksums over garbage: the decoder's own checks must hold (a crafted file can carry
// correct checksums). Random sections behind a correct header and trailer.
TEST(TrellisBlockCodec, DecodesRandomSectionsWithoutCrashing) {
  std::mt19937_64 rng(99);
  const TrellisColumns columns = MakeRunColumns(64, 1.0f, 5, 40, 17);
  const Encoded encoded = EncodeBlock(0, columns, 1.0f);
  int rejected = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Encoded damaged = encoded;
    const size_t body_begin = trellis_file::kBlockHeaderBytes;
    const size_t body_end = damaged.bytes.size() - trellis_file::kBlockTrailerBytes;
    const int flips = 1 + static_cast<int>(rng() % 8);
    for (int flip = 0; flip < flips; ++flip) {
      damaged.bytes[body_begin + rng() % (body_end - body_begin)] = static_cast<char>(rng());
    }
    // Re-seal: a correct checksum over the damage.
    const uint64_t checksum = trellis_file::Checksum64(damaged.bytes.data(), body_end);
    damaged.bytes.resize(body_end);
    trellis_file::PutU64(&damaged.bytes, checksum);
    damaged.handle.checksum = checksum;
    TrellisBlock block;
    const Status status = Decode(damaged, Limits(64, 1000, 1.0f), &block);
    if (!status.ok()) {
      ASSERT_TRUE(status.IsCorruption()) << status.ToString();
      ++rejected;
    }
  }
  EXPECT_GT(rejected, 1000);
}

}  // namespace
}  // namespace motif::testing
