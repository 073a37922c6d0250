#include "formats/frame_file/column_codec.h"

#include <bit>
#include <cmath>
#include <vector>

#include <zstd.h>

namespace motif::frame_file {
namespace {

// The largest |round(value / step)| stored: the int32 range (INT32_MIN excluded so the range is
// symmetric and the check is one comparison).
constexpr double kMaxQuantized = 2147483647.0;

bool Quantize(const ColumnEncoding& encoding, float value, int32_t* quantized) {
  if (!std::isfinite(value)) return false;
  const double scaled = std::round(static_cast<double>(value) / encoding.step);
  if (!(std::fabs(scaled) <= kMaxQuantized)) return false;
  *quantized = static_cast<int32_t>(scaled);
  return true;
}

float Dequantize(const ColumnEncoding& encoding, int32_t quantized) {
  return static_cast<float>(static_cast<double>(quantized) * encoding.step);
}

uint32_t ZigZag(uint32_t word) {
  return (word << 1) ^ static_cast<uint32_t>(static_cast<int32_t>(word) >> 31);
}

uint32_t UnZigZag(uint32_t code) { return (code >> 1) ^ (0u - (code & 1u)); }

// Delta along time, in place, on each component's run of `frame_count` words. Pass p (1-based)
// replaces x[i] by x[i] - x[i-1] for i >= p, so with order 2 the residuals are x[0], x[1] - x[0],
// then the second differences x[i] - 2 x[i-1] + x[i-2].
void ApplyDelta(uint32_t* words, uint32_t component_count, uint32_t frame_count, int order) {
  for (int pass = 1; pass <= order; ++pass) {
    for (uint32_t component = 0; component < component_count; ++component) {
      uint32_t* run = words + static_cast<size_t>(component) * frame_count;
      for (uint32_t frame_idx = frame_count; frame_idx-- > static_cast<uint32_t>(pass);) {
        run[frame_idx] -= run[frame_idx - 1];
      }
    }
  }
}

void UndoDelta(uint32_t* words, uint32_t component_count, uint32_t frame_count, int order) {
  for (int pass = order; pass >= 1; --pass) {
    for (uint32_t component = 0; component < component_count; ++component) {
      uint32_t* run = words + static_cast<size_t>(component) * frame_count;
      for (uint32_t frame_idx = static_cast<uint32_t>(pass); frame_idx < frame_count; ++frame_idx) {
        run[frame_idx] += run[frame_idx - 1];
      }
    }
  }
}

struct DCtxDeleter {
  void operator()(ZSTD_DCtx* context) const { ZSTD_freeDCtx(context); }
};

struct DecodeScratch {
  std::unique_ptr<ZSTD_DCtx, DCtxDeleter> context;
  std::vector<uint8_t> bytes;
  std::vector<uint32_t> words;
};

DecodeScratch& ThreadScratch() {
  thread_local DecodeScratch scratch;
  if (!scratch.context) scratch.context.reset(ZSTD_createDCtx());
  return scratch;
}

}  // namespace

Status ValidateEncoding(const ColumnEncoding& encoding, uint32_t component_count) {
  if (encoding.quantization != Quantization::kNone &&
      encoding.quantization != Quantization::kUniform) {
    return Status::InvalidArgument("unknown quantization " +
                                   std::to_string(static_cast<int>(encoding.quantization)));
  }
  if (encoding.compression != Compression::kNone && encoding.compression != Compression::kZstd) {
    return Status::InvalidArgument("unknown compression " +
                                   std::to_string(static_cast<int>(encoding.compression)));
  }
  if (encoding.delta_order > kMaxDeltaOrder) {
    return Status::InvalidArgument("delta order " + std::to_string(encoding.delta_order) +
                                   " (at most 2)");
  }
  if (encoding.quantization == Quantization::kUniform) {
    if (!std::isfinite(encoding.step) || !(encoding.step > 0)) {
      return Status::InvalidArgument("quantisation step must be finite and > 0");
    }
  } else if (std::bit_cast<uint64_t>(encoding.step) != 0) {
    return Status::InvalidArgument("quantisation step must be 0 without quantisation");
  }
  if (encoding.normalize &&
      (component_count != 4 || encoding.quantization != Quantization::kUniform)) {
    return Status::InvalidArgument("normalize needs a quantised 4-component column");
  }
  if (component_count == 0) return Status::InvalidArgument("a column needs components");
  return Status::Ok();
}

bool IsEncodable(const ColumnEncoding& encoding, float value) {
  if (!std::isfinite(value)) return false;
  if (encoding.quantization == Quantization::kNone) return true;
  int32_t quantized = 0;
  return Quantize(encoding, value, &quantized);
}

float QuantizeRoundTrip(const ColumnEncoding& encoding, float value) {
  if (encoding.quantization == Quantization::kNone) return value;
  int32_t quantized = 0;
  if (!Quantize(encoding, value, &quantized)) return value;
  return Dequantize(encoding, quantized);
}

bool IsValidZstdLevel(int level) { return level >= ZSTD_minCLevel() && level <= ZSTD_maxCLevel(); }

class ColumnEncoder::Impl {
 public:
  explicit Impl(int zstd_level) : zstd_level_(zstd_level), context_(ZSTD_createCCtx()) {}
  ~Impl() { ZSTD_freeCCtx(context_); }

  Status Encode(const ColumnEncoding& encoding, const float* values, uint32_t component_count,
                uint32_t frame_count, std::string* out) {
    const size_t word_count = static_cast<size_t>(component_count) * frame_count;
    words_.resize(word_count);
    for (size_t word_idx = 0; word_idx < word_count; ++word_idx) {
      const float value = values[word_idx];
      if (!std::isfinite(value)) {
        return Status::InvalidArgument("value " + std::to_string(value) + " is not finite");
      }
      if (encoding.quantization == Quantization::kUniform) {
        int32_t quantized = 0;
        if (!Quantize(encoding, value, &quantized)) {
          return Status::InvalidArgument("value " + std::to_string(value) +
                                         " overflows int32 when quantised with step " +
                                         std::to_string(encoding.step));
        }
        words_[word_idx] = static_cast<uint32_t>(quantized);
      } else {
        words_[word_idx] = std::bit_cast<uint32_t>(value);
      }
    }
    ApplyDelta(words_.data(), component_count, frame_count, encoding.delta_order);
    if (encoding.zigzag) {
      for (uint32_t& word : words_) word = ZigZag(word);
    }
    bytes_.resize(word_count * 4);
    if (encoding.shuffle) {
      for (size_t word_idx = 0; word_idx < word_count; ++word_idx) {
        for (size_t plane = 0; plane < 4; ++plane) {
          bytes_[plane * word_count + word_idx] =
              static_cast<uint8_t>(words_[word_idx] >> (8 * plane));
        }
      }
    } else {
      for (size_t word_idx = 0; word_idx < word_count; ++word_idx) {
        for (size_t byte_idx = 0; byte_idx < 4; ++byte_idx) {
          bytes_[word_idx * 4 + byte_idx] =
              static_cast<uint8_t>(words_[word_idx] >> (8 * byte_idx));
        }
      }
    }
    if (encoding.compression == Compression::kNone) {
      out->append(reinterpret_cast<const char*>(bytes_.data()), bytes_.size());
      return Status::Ok();
    }
    if (context_ == nullptr) return Status::ResourceExhausted("cannot create a zstd context");
    ZSTD_CCtx_reset(context_, ZSTD_reset_session_and_parameters);
    ZSTD_CCtx_setParameter(context_, ZSTD_c_compressionLevel, zstd_level_);
    ZSTD_CCtx_setParameter(context_, ZSTD_c_contentSizeFlag, 1);
    ZSTD_CCtx_setParameter(context_, ZSTD_c_checksumFlag, 0);  // the block checksum covers it
    ZSTD_CCtx_setParameter(context_, ZSTD_c_dictIDFlag, 0);
    const size_t start = out->size();
    out->resize(start + ZSTD_compressBound(bytes_.size()));
    const size_t written = ZSTD_compress2(context_, out->data() + start, out->size() - start,
                                          bytes_.data(), bytes_.size());
    if (ZSTD_isError(written)) {
      out->resize(start);
      return Status::ResourceExhausted(std::string("zstd compression failed: ") +
                                       ZSTD_getErrorName(written));
    }
    out->resize(start + written);
    return Status::Ok();
  }

 private:
  int zstd_level_;
  ZSTD_CCtx* context_;
  std::vector<uint32_t> words_;
  std::vector<uint8_t> bytes_;
};

ColumnEncoder::ColumnEncoder(int zstd_level) : impl_(std::make_unique<Impl>(zstd_level)) {}
ColumnEncoder::~ColumnEncoder() = default;

Status ColumnEncoder::Encode(const ColumnEncoding& encoding, const float* values,
                             uint32_t component_count, uint32_t frame_count, std::string* out) {
  return impl_->Encode(encoding, values, component_count, frame_count, out);
}

Status DecodeColumnChunk(const ColumnEncoding& encoding, const uint8_t* chunk, size_t chunk_bytes,
                         uint32_t component_count, uint32_t frame_count, float* values) {
  const size_t word_count = static_cast<size_t>(component_count) * frame_count;
  const size_t raw_bytes = word_count * 4;
  DecodeScratch& scratch = ThreadScratch();
  const uint8_t* bytes = chunk;
  if (encoding.compression == Compression::kZstd) {
    if (!scratch.context) return Status::ResourceExhausted("cannot create a zstd context");
    const unsigned long long content_size = ZSTD_getFrameContentSize(chunk, chunk_bytes);
    if (content_size == ZSTD_CONTENTSIZE_ERROR || content_size == ZSTD_CONTENTSIZE_UNKNOWN) {
      return Status::Corruption("column chunk is not a zstd frame with a content size");
    }
    if (content_size != raw_bytes) {
      return Status::Corruption("column chunk holds " + std::to_string(content_size) +
                                " bytes, expected " + std::to_string(raw_bytes));
    }
    const size_t frame_bytes = ZSTD_findFrameCompressedSize(chunk, chunk_bytes);
    if (ZSTD_isError(frame_bytes) || frame_bytes != chunk_bytes) {
      return Status::Corruption("column chunk is not exactly one zstd frame");
    }
    scratch.bytes.resize(raw_bytes);
    const size_t decoded = ZSTD_decompressDCtx(scratch.context.get(), scratch.bytes.data(),
                                               raw_bytes, chunk, chunk_bytes);
    if (ZSTD_isError(decoded) || decoded != raw_bytes) {
      return Status::Corruption(
          std::string("column chunk does not decode: ") +
          (ZSTD_isError(decoded) ? ZSTD_getErrorName(decoded) : "wrong size"));
    }
    bytes = scratch.bytes.data();
  } else if (chunk_bytes != raw_bytes) {
    return Status::Corruption("stored column chunk has " + std::to_string(chunk_bytes) +
                              " bytes, expected " + std::to_string(raw_bytes));
  }

  std::vector<uint32_t>& words = scratch.words;
  words.resize(word_count);
  if (encoding.shuffle) {
    for (size_t word_idx = 0; word_idx < word_count; ++word_idx) {
      words[word_idx] = static_cast<uint32_t>(bytes[word_idx]) |
                        static_cast<uint32_t>(bytes[word_count + word_idx]) << 8 |
                        static_cast<uint32_t>(bytes[2 * word_count + word_idx]) << 16 |
                        static_cast<uint32_t>(bytes[3 * word_count + word_idx]) << 24;
    }
  } else {
    for (size_t word_idx = 0; word_idx < word_count; ++word_idx) {
      const uint8_t* word_bytes = bytes + 4 * word_idx;
      words[word_idx] =
          static_cast<uint32_t>(word_bytes[0]) | static_cast<uint32_t>(word_bytes[1]) << 8 |
          static_cast<uint32_t>(word_bytes[2]) << 16 | static_cast<uint32_t>(word_bytes[3]) << 24;
    }
  }
  if (encoding.zigzag) {
    for (uint32_t& word : words) word = UnZigZag(word);
  }
  UndoDelta(words.data(), component_count, frame_count, encoding.delta_order);
  if (encoding.quantization == Quantization::kUniform) {
    for (size_t word_idx = 0; word_idx < word_count; ++word_idx) {
      values[word_idx] = Dequantize(encoding, static_cast<int32_t>(words[word_idx]));
    }
  } else {
    for (size_t word_idx = 0; word_idx < word_count; ++word_idx) {
      values[word_idx] = std::bit_cast<float>(words[word_idx]);
    }
  }
  if (encoding.normalize) {
    // Component-major: the quaternion of frame f is values[f], [n + f], [2n + f], [3n + f].
    const size_t n = frame_count;
    for (size_t frame_idx = 0; frame_idx < n; ++frame_idx) {
      float* w = values + frame_idx;
      const double c0 = w[0], c1 = w[n], c2 = w[2 * n], c3 = w[3 * n];
      const double norm = std::sqrt(((c0 * c0 + c1 * c1) + c2 * c2) + c3 * c3);
      if (norm > 0) {
        w[0] = static_cast<float>(c0 / norm);
        w[n] = static_cast<float>(c1 / norm);
        w[2 * n] = static_cast<float>(c2 / norm);
        w[3 * n] = static_cast<float>(c3 / norm);
      }
    }
  }
  return Status::Ok();
}

}  // namespace motif::frame_file
