#include "bench/studies/column_distances.h"

#include <algorithm>

namespace motif::testing {
namespace {

uint32_t NearestColumn(const ColumnGrid& grid, double frame) {
  const double column = std::round((frame - grid.first_centre) / grid.spacing);
  return static_cast<uint32_t>(std::clamp(column, 0.0, static_cast<double>(grid.count - 1)));
}

// z-normalises `count` values `stride` apart in place; the deviation at least `floor`.
void ZNormalise(float* values, uint32_t count, uint32_t stride, double floor) {
  double mean = 0;
  for (uint32_t idx = 0; idx < count; ++idx) mean += values[idx * stride];
  mean /= count;
  double variance = 0;
  for (uint32_t idx = 0; idx < count; ++idx) {
    variance += (values[idx * stride] - mean) * (values[idx * stride] - mean);
  }
  const double deviation = std::max(std::sqrt(variance / count), floor);
  for (uint32_t idx = 0; idx < count; ++idx) {
    values[idx * stride] = static_cast<float>((values[idx * stride] - mean) / deviation);
  }
}

}  // namespace

uint32_t ColumnGrid::DefaultCount(const Span& span) const {
  const double length = static_cast<double>(span.length());
  if (kind == Kind::kWords) {
    return std::clamp<uint32_t>(static_cast<uint32_t>(std::lround(length / word_spacing)), 1,
                                samples);
  }
  return std::clamp<uint32_t>(static_cast<uint32_t>(std::ceil(length / spacing)), 2, samples);
}

std::vector<uint32_t> ColumnGrid::Columns(const Span& span, uint32_t wanted) const {
  const uint32_t m = wanted > 0 ? wanted : DefaultCount(span);
  const double length = static_cast<double>(span.length());
  std::vector<uint32_t> columns(m);
  for (uint32_t idx = 0; idx < m; ++idx) {
    double frame = 0;
    if (kind == Kind::kWords || m == 1) {
      frame = span.start + (idx + 0.5) * length / m;
    } else {
      frame = span.start + std::round(idx * (length - 1) / (m - 1));
    }
    columns[idx] = NearestColumn(*this, frame);
  }
  return columns;
}

QuatColumns::QuatColumns(const PoseFeatures& features, uint64_t first_frame, const ColumnGrid& grid,
                         uint64_t clip_frames)
    : features_(&features) {
  for (uint32_t column = 0; column < grid.count; ++column) {
    const auto frame = static_cast<uint64_t>(std::lround(grid.Centre(column)));
    frames_.push_back(first_frame + std::min(frame, clip_frames - 1));
  }
}

VectorColumns BodyColumns(const BodyFrameFeatures& body, const ChannelSet& channels,
                          const ColumnGrid& grid) {
  const auto dims = static_cast<uint32_t>(channels.size());
  std::vector<float> values(size_t{grid.count} * dims);
  for (uint32_t column = 0; column < grid.count; ++column) {
    const auto frame = std::min<uint64_t>(static_cast<uint64_t>(std::lround(grid.Centre(column))),
                                          body.frame_count() - 1);
    const float* source = body.frame(frame);
    for (uint32_t idx = 0; idx < dims; ++idx)
      values[size_t{column} * dims + idx] = source[channels[idx]];
  }
  return VectorColumns(std::move(values), dims, 1.0 / dims);
}

VectorColumns ZNormalisedWindowColumns(const BodyFrameFeatures& body, const ChannelSet& channels,
                                       const ColumnGrid& grid, uint32_t window_samples,
                                       double sample_frames, double floor) {
  const auto channel_count = static_cast<uint32_t>(channels.size());
  const uint32_t dims = channel_count * window_samples;
  std::vector<float> values(size_t{grid.count} * dims);
  const auto last = static_cast<double>(body.frame_count() - 1);
  for (uint32_t column = 0; column < grid.count; ++column) {
    float* out = &values[size_t{column} * dims];  // [sample][channel]
    for (uint32_t sample = 0; sample < window_samples; ++sample) {
      const double offset = (sample - 0.5 * (window_samples - 1)) * sample_frames;
      const auto frame =
          static_cast<uint64_t>(std::clamp(std::round(grid.Centre(column) + offset), 0.0, last));
      const float* source = body.frame(frame);
      for (uint32_t idx = 0; idx < channel_count; ++idx) {
        out[sample * channel_count + idx] = source[channels[idx]];
      }
    }
    for (uint32_t idx = 0; idx < channel_count; ++idx) {
      ZNormalise(out + idx, window_samples, channel_count, floor);
    }
  }
  return VectorColumns(std::move(values), dims, 1.0 / dims);
}

ColumnMatrix::ColumnMatrix(const ColumnDistance& distance) : n_(distance.count()) {
  values_.assign(size_t{n_} * n_, 0.0f);
  for (uint32_t a = 0; a < n_; ++a) {
    for (uint32_t b = a + 1; b < n_; ++b) {
      values_[size_t{a} * n_ + b] = values_[size_t{b} * n_ + a] = distance.Distance(a, b);
    }
  }
}

std::vector<float> ZNormalisedStretch(const BodyFrameFeatures& body, const ChannelSet& channels,
                                      const Span& span, uint32_t samples, double floor) {
  const auto channel_count = static_cast<uint32_t>(channels.size());
  std::vector<float> values(size_t{channel_count} * samples);
  const double length = static_cast<double>(span.length());
  for (uint32_t sample = 0; sample < samples; ++sample) {
    const auto frame = std::min<uint64_t>(
        span.start + static_cast<uint64_t>(std::round(sample * (length - 1) / (samples - 1))),
        body.frame_count() - 1);
    const float* source = body.frame(frame);
    for (uint32_t idx = 0; idx < channel_count; ++idx) {
      values[size_t{idx} * samples + sample] = source[channels[idx]];
    }
  }
  for (uint32_t idx = 0; idx < channel_count; ++idx) {
    ZNormalise(&values[size_t{idx} * samples], samples, 1, floor);
  }
  return values;
}

float RootMeanSquareDifference(const std::vector<float>& a, const std::vector<float>& b) {
  float sum = 0;
  for (size_t idx = 0; idx < a.size(); ++idx) sum += (a[idx] - b[idx]) * (a[idx] - b[idx]);
  return std::sqrt(sum / static_cast<float>(a.size()));
}

}  // namespace motif::testing
