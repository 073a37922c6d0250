#include "engine/signature/time_warp.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/split_mix64.h"

namespace motif {

Status ValidateTimeWarpOptions(const TimeWarpOptions& options) {
  for (double speed : {options.min_speed, options.max_speed}) {
    if (!std::isfinite(speed) || speed <= 0) {
      return Status::InvalidArgument("time warp: speeds must be finite and positive, not " +
                                     std::to_string(speed));
    }
  }
  if (options.min_speed > options.max_speed) {
    return Status::InvalidArgument("time warp: min_speed " + std::to_string(options.min_speed) +
                                   " is above max_speed " + std::to_string(options.max_speed));
  }
  return Status::Ok();
}

double DrawWarpSpeed(uint64_t seed, const TimeWarpOptions& options) {
  MOTIF_CHECK(ValidateTimeWarpOptions(options).ok());
  if (options.min_speed == options.max_speed) return options.min_speed;
  SplitMix64 random(seed);
  const double low = std::log(options.min_speed);
  const double high = std::log(options.max_speed);
  const double speed = std::exp(low + random.Uniform() * (high - low));
  return std::clamp(speed, options.min_speed, options.max_speed);
}

std::vector<double> WarpedSamplePositions(const WordGrid& grid, uint64_t word_idx, double speed) {
  MOTIF_CHECK(word_idx < grid.word_count());
  MOTIF_CHECK(std::isfinite(speed) && speed > 0);
  const uint32_t word_frames = grid.options().word_frames;
  const double half = 0.5 * static_cast<double>(word_frames - 1);
  // Small integers and halves: exact in double, so at speed 1 u_j = w S + j exactly.
  const double centre = static_cast<double>(grid.FirstSample(word_idx)) + half;
  std::vector<double> positions(word_frames);
  for (uint32_t frame = 0; frame < word_frames; ++frame) {
    positions[frame] = centre + (static_cast<double>(frame) - half) * speed;
  }
  const double last = grid.last_sample_position();
  double shift = 0;
  if (positions.back() - positions.front() > last) {
    shift = 0.5 * last - centre;  // longer than the clip: centre it, Locate clamps the ends
  } else if (positions.front() < 0) {
    shift = -positions.front();
  } else if (positions.back() > last) {
    shift = last - positions.back();
  }
  if (shift != 0) {
    for (double& position : positions) position += shift;
  }
  return positions;
}

void WarpWord(const WordGrid& grid, const FrameResampler& resampler, const float* clip_rows,
              uint64_t word_idx, double speed, int16_t* features, float* rows) {
  const size_t stride = resampler.layout().stride();
  const size_t feature_values = resampler.feature_values();
  const std::vector<double> positions = WarpedSamplePositions(grid, word_idx, speed);
  for (size_t frame = 0; frame < positions.size(); ++frame) {
    const SourcePosition position = grid.Locate(grid.SourceTime(positions[frame]));
    const float* lower = clip_rows + position.lower * stride;
    const float* upper = clip_rows + position.upper * stride;
    int16_t* out = features + frame * feature_values;
    if (rows != nullptr) {
      float* row = rows + frame * stride;
      resampler.InterpolateRow(lower, upper, position.alpha, row);
      resampler.RowFeatures(row, out);
    } else {
      resampler.InterpolateFeatures(lower, upper, position.alpha, out);
    }
  }
}

}  // namespace motif
