#include "formats/frame_file/column_codec.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace motif::frame_file {
namespace {

std::vector<float> SmoothValues(uint32_t component_count, uint32_t frame_count, double scale) {
  std::vector<float> values(static_cast<size_t>(component_count) * frame_count);
  for (uint32_t component = 0; component < component_count; ++component) {
    for (uint32_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
      values[component * frame_count + frame_idx] =
          static_cast<float>(scale * std::sin(0.01 * frame_idx + component));
    }
  }
  return values;
}

ColumnEncoding Quantised(double step) {
  ColumnEncoding encoding;
  encoding.step = step;
  return encoding;
}

ColumnEncoding Lossless() {
  ColumnEncoding encoding;
  encoding.quantization = Quantization::kNone;
  encoding.step = 0;
  return encoding;
}

std::string Encode(const ColumnEncoding& encoding, const std::vector<float>& values,
                   uint32_t component_count) {
  ColumnEncoder encoder(3);
  std::string chunk;
  const uint32_t frame_count = static_cast<uint32_t>(values.size() / component_count);
  Status status = encoder.Encode(encoding, values.data(), component_count, frame_count, &chunk);
  EXPECT_TRUE(status.ok()) << status.ToString();
  return chunk;
}

std::vector<float> Decode(const ColumnEncoding& encoding, const std::string& chunk,
                          uint32_t component_count, uint32_t frame_count) {
  std::vector<float> values(static_cast<size_t>(component_count) * frame_count);
  Status status = DecodeColumnChunk(encoding, reinterpret_cast<const uint8_t*>(chunk.data()),
                                    chunk.size(), component_count, frame_count, values.data());
  EXPECT_TRUE(status.ok()) << status.ToString();
  return values;
}

TEST(ColumnCodec, QuantisedRoundTripIsWithinHalfAStep) {
  const std::vector<float> values = SmoothValues(2, 500, 40.0);
  for (double step : {1e-3, 1e-4, 1.0 / 32768}) {
    const ColumnEncoding encoding = Quantised(step);
    const std::vector<float> decoded = Decode(encoding, Encode(encoding, values, 2), 2, 500);
    for (size_t index = 0; index < values.size(); ++index) {
      EXPECT_LE(std::fabs(static_cast<double>(values[index]) - decoded[index]),
                step / 2 + std::fabs(values[index]) * 1.2e-7)
          << "step " << step << " index " << index;
      EXPECT_EQ(decoded[index], QuantizeRoundTrip(encoding, values[index]));
    }
  }
}

TEST(ColumnCodec, PowerOfTwoStepIsExactlyHalfAStep) {
  const double step = 1.0 / 32768;
  const std::vector<float> values = SmoothValues(1, 300, 1.0);
  const ColumnEncoding encoding = Quantised(step);
  const std::vector<float> decoded = Decode(encoding, Encode(encoding, values, 1), 1, 300);
  for (size_t index = 0; index < values.size(); ++index) {
    EXPECT_LE(std::fabs(static_cast<double>(values[index]) - decoded[index]), step / 2);
  }
}

TEST(ColumnCodec, EveryTransformCombinationRoundTrips) {
  const std::vector<float> values = SmoothValues(4, 257, 1.0);
  const ColumnEncoding reference = Quantised(1e-4);
  for (bool quantise : {false, true}) {
    for (uint8_t delta_order = 0; delta_order <= kMaxDeltaOrder; ++delta_order) {
      for (bool zigzag : {false, true}) {
        for (bool shuffle : {false, true}) {
          for (Compression compression : {Compression::kNone, Compression::kZstd}) {
            ColumnEncoding encoding = quantise ? Quantised(1e-4) : Lossless();
            encoding.delta_order = delta_order;
            encoding.zigzag = zigzag;
            encoding.shuffle = shuffle;
            encoding.compression = compression;
            ASSERT_TRUE(ValidateEncoding(encoding, 4).ok());
            const std::string chunk = Encode(encoding, values, 4);
            if (compression == Compression::kNone) {
              EXPECT_EQ(chunk.size(), values.size() * 4);
            }
            const std::vector<float> decoded = Decode(encoding, chunk, 4, 257);
            for (size_t index = 0; index < values.size(); ++index) {
              const float expected =
                  quantise ? QuantizeRoundTrip(reference, values[index]) : values[index];
              ASSERT_EQ(std::memcmp(&expected, &decoded[index], 4), 0)
                  << "quantise " << quantise << " delta " << int{delta_order} << " zigzag "
                  << zigzag << " shuffle " << shuffle << " index " << index;
            }
          }
        }
      }
    }
  }
}

TEST(ColumnCodec, LosslessKeepsEveryFloatBitPattern) {
  std::vector<float> values = {0.0f,
                               -0.0f,
                               1.0f,
                               -1.0f,
                               std::numeric_limits<float>::denorm_min(),
                               std::numeric_limits<float>::max(),
                               std::numeric_limits<float>::lowest(),
                               1e-30f,
                               3.14159f,
                               -2.5e7f};
  const ColumnEncoding encoding = Lossless();
  const std::vector<float> decoded =
      Decode(encoding, Encode(encoding, values, 1), 1, static_cast<uint32_t>(values.size()));
  ASSERT_EQ(decoded.size(), values.size());
  EXPECT_EQ(std::memcmp(decoded.data(), values.data(), values.size() * 4), 0);
}

TEST(ColumnCodec, DeltasThatOverflowInt32WrapAround) {
  // Quantised values at both ends of the int32 range: their differences overflow int32.
  const double step = 1.0;
  std::vector<float> values;
  for (int frame_idx = 0; frame_idx < 64; ++frame_idx) {
    values.push_back(frame_idx % 2 == 0 ? 2147483520.0f : -2147483520.0f);
  }
  for (uint8_t delta_order : {1, 2}) {
    ColumnEncoding encoding = Quantised(step);
    encoding.delta_order = delta_order;
    const std::vector<float> decoded = Decode(encoding, Encode(encoding, values, 1), 1, 64);
    EXPECT_EQ(decoded, values);
  }
}

TEST(ColumnCodec, NormalizeRescalesEachQuaternion) {
  const uint32_t frame_count = 100;
  std::vector<float> values(4 * frame_count);
  for (uint32_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    const double angle = 0.05 * frame_idx;
    values[frame_idx] = static_cast<float>(std::cos(angle / 2));
    values[frame_count + frame_idx] = static_cast<float>(0.6 * std::sin(angle / 2));
    values[2 * frame_count + frame_idx] = 0;
    values[3 * frame_count + frame_idx] = static_cast<float>(0.8 * std::sin(angle / 2));
  }
  ColumnEncoding encoding = Quantised(1.0 / 32768);
  encoding.normalize = true;
  ASSERT_TRUE(ValidateEncoding(encoding, 4).ok());
  const std::vector<float> decoded = Decode(encoding, Encode(encoding, values, 4), 4, frame_count);
  for (uint32_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    double norm = 0, input_norm = 0, dot = 0;
    for (uint32_t component = 0; component < 4; ++component) {
      const double value = decoded[component * frame_count + frame_idx];
      const double input = values[component * frame_count + frame_idx];
      norm += value * value;
      input_norm += input * input;
      dot += value * input;
    }
    EXPECT_NEAR(norm, 1.0, 1e-6);
    const double cosine = std::min(1.0, std::fabs(dot) / std::sqrt(norm * input_norm));
    EXPECT_LE(2 * std::acos(cosine), 4.0 / 32768);
  }
}

TEST(ColumnCodec, RejectsNonFiniteValues) {
  ColumnEncoder encoder(3);
  std::string chunk;
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                    -std::numeric_limits<float>::infinity()}) {
    const std::vector<float> values = {1.0f, bad, 2.0f};
    EXPECT_FALSE(IsEncodable(Quantised(1e-3), bad));
    EXPECT_FALSE(IsEncodable(Lossless(), bad));
    EXPECT_TRUE(encoder.Encode(Quantised(1e-3), values.data(), 1, 3, &chunk).IsInvalidArgument());
    EXPECT_TRUE(encoder.Encode(Lossless(), values.data(), 1, 3, &chunk).IsInvalidArgument());
  }
}

TEST(ColumnCodec, RejectsValuesWhoseQuantisedValueOverflowsInt32) {
  const ColumnEncoding encoding = Quantised(1e-5);
  EXPECT_TRUE(IsEncodable(encoding, 21474.0f));
  EXPECT_FALSE(IsEncodable(encoding, 21475.0f));
  EXPECT_FALSE(IsEncodable(encoding, -21475.0f));
  ColumnEncoder encoder(3);
  std::string chunk;
  const std::vector<float> values = {0.0f, 30000.0f};
  Status status = encoder.Encode(encoding, values.data(), 1, 2, &chunk);
  EXPECT_TRUE(status.IsInvalidArgument());
  EXPECT_NE(status.message().find("overflows int32"), std::string::npos) << status.message();
}

TEST(ColumnCodec, ValidateEncodingRejectsInconsistentEncodings) {
  ColumnEncoding encoding = Quantised(0);
  EXPECT_TRUE(ValidateEncoding(encoding, 1).IsInvalidArgument());
  encoding = Quantised(std::numeric_limits<double>::infinity());
  EXPECT_TRUE(ValidateEncoding(encoding, 1).IsInvalidArgument());
  encoding = Lossless();
  encoding.step = 1e-3;
  EXPECT_TRUE(ValidateEncoding(encoding, 1).IsInvalidArgument());
  encoding = Quantised(1e-3);
  encoding.delta_order = 3;
  EXPECT_TRUE(ValidateEncoding(encoding, 1).IsInvalidArgument());
  encoding = Quantised(1e-3);
  encoding.normalize = true;
  EXPECT_TRUE(ValidateEncoding(encoding, 2).IsInvalidArgument());
  encoding = Quantised(1e-3);
  encoding.compression = static_cast<Compression>(7);
  EXPECT_TRUE(ValidateEncoding(encoding, 1).IsInvalidArgument());
  encoding = Quantised(1e-3);
  encoding.quantization = static_cast<Quantization>(9);
  EXPECT_TRUE(ValidateEncoding(encoding, 1).IsInvalidArgument());
  EXPECT_TRUE(ValidateEncoding(Quantised(1e-3), 0).IsInvalidArgument());
}

TEST(ColumnCodec, DecodeRejectsChunksOfTheWrongSize) {
  const std::vector<float> values = SmoothValues(1, 100, 1.0);
  const ColumnEncoding encoding = Quantised(1e-4);
  const std::string chunk = Encode(encoding, values, 1);
  std::vector<float> out(200);
  const auto* bytes = reinterpret_cast<const uint8_t*>(chunk.data());
  // Claims another frame count than the chunk holds.
  EXPECT_TRUE(DecodeColumnChunk(encoding, bytes, chunk.size(), 1, 99, out.data()).IsCorruption());
  EXPECT_TRUE(DecodeColumnChunk(encoding, bytes, chunk.size(), 2, 100, out.data()).IsCorruption());
  // Trailing or missing bytes.
  const std::string longer = chunk + "x";
  EXPECT_TRUE(DecodeColumnChunk(encoding, reinterpret_cast<const uint8_t*>(longer.data()),
                                longer.size(), 1, 100, out.data())
                  .IsCorruption());
  EXPECT_TRUE(
      DecodeColumnChunk(encoding, bytes, chunk.size() - 1, 1, 100, out.data()).IsCorruption());
  ColumnEncoding stored = encoding;
  stored.compression = Compression::kNone;
  EXPECT_TRUE(DecodeColumnChunk(stored, bytes, 17, 1, 100, out.data()).IsCorruption());
}

TEST(ColumnCodec, RandomBytesNeverDecodeSilentlyOrCrash) {
  std::mt19937 random(7);
  const ColumnEncoding encoding = Quantised(1e-4);
  constexpr uint32_t kComponents = 4;
  constexpr uint32_t kFrames = 64;
  constexpr size_t kValues = kComponents * kFrames;
  constexpr size_t kGuard = 64;  // floats after the chunk's values that a decode must not touch
  const float kUnwritten = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> out(kValues + kGuard);
  int rejected = 0;
  for (int trial = 0; trial < 500; ++trial) {
    std::string bytes(random() % 200, '\0');
    for (char& byte : bytes) byte = static_cast<char>(random());
    if (trial % 2 == 0 && bytes.size() >= 4) {
      const char magic[4] = {0x28, static_cast<char>(0xb5), 0x2f, static_cast<char>(0xfd)};
      std::memcpy(bytes.data(), magic, 4);  // a zstd magic, then garbage
    }
    std::fill(out.begin(), out.end(), kUnwritten);
    const auto* chunk = reinterpret_cast<const uint8_t*>(bytes.data());
    // Whatever the outcome, no crash, and nothing written past the chunk's values.
    const Status status =
        DecodeColumnChunk(encoding, chunk, bytes.size(), kComponents, kFrames, out.data());
    for (size_t idx = kValues; idx < out.size(); ++idx) {
      ASSERT_TRUE(std::isnan(out[idx])) << "trial " << trial << ": wrote past the values";
    }
    if (!status.ok()) {
      // Rejected: as Corruption, with a message that says what is wrong with the chunk.
      EXPECT_TRUE(status.IsCorruption()) << "trial " << trial << ": " << status.ToString();
      EXPECT_NE(status.message().find("column chunk"), std::string::npos)
          << "trial " << trial << ": " << status.ToString();
      ++rejected;
      continue;
    }
    // Accepted: only a chunk of exactly this size. Every value is written (a dequantised value
    // is never NaN), and the same bytes are refused as a chunk of one frame fewer.
    for (size_t idx = 0; idx < kValues; ++idx) {
      ASSERT_FALSE(std::isnan(out[idx])) << "trial " << trial << ": value " << idx << " unset";
    }
    EXPECT_TRUE(
        DecodeColumnChunk(encoding, chunk, bytes.size(), kComponents, kFrames - 1, out.data())
            .IsCorruption())
        << "trial " << trial << ": decoded as two different sizes";
  }
  // With this seed none of the 500 is a zstd frame of 1024 bytes: all are rejected.
  RecordProperty("rejected", rejected);
}

}  // namespace
}  // namespace motif::frame_file
