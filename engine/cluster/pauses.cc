#include "engine/cluster/pauses.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "engine/distance/pose_features.h"

namespace motif {

namespace {

// Frames read at once per clip; chunks overlap by the speed window so every frame sees both
// of its neighbours.
constexpr uint64_t kChunkFrames = 8192;

uint64_t HalfWindow(double fps) {
  return std::max<uint64_t>(1, static_cast<uint64_t>(std::lround(0.025 * fps)));
}

// Appends the runs of at least min_frames slow frames of speeds[0, count) to `pauses`, frame
// numbers offset by `first`; a run still open at the end is carried in *run_start (the global
// frame it began at), so runs continue across chunks.
void CollectRuns(const std::vector<double>& speeds, uint64_t first, uint64_t count,
                 double max_speed, uint64_t min_frames, uint64_t* run_start, bool* in_run,
                 std::vector<MotifInstance>* pauses) {
  for (uint64_t idx = 0; idx < count; ++idx) {
    const uint64_t frame = first + idx;
    if (speeds[idx] < max_speed) {
      if (!*in_run) *run_start = frame;
      *in_run = true;
    } else if (*in_run) {
      if (frame - *run_start >= min_frames) pauses->push_back({*run_start, frame});
      *in_run = false;
    }
  }
}

}  // namespace

Status ValidatePauseOptions(const PauseOptions& options) {
  if (!std::isfinite(options.max_speed) || options.max_speed < 0) {
    return Status::InvalidArgument("the pause speed must be a finite number >= 0");
  }
  if (!std::isfinite(options.min_seconds) || options.min_seconds <= 0) {
    return Status::InvalidArgument("the shortest pause must be a finite number of seconds > 0");
  }
  return Status::Ok();
}

std::vector<double> FrameSpeeds(const float* rows, uint64_t frame_count, uint32_t joint_count,
                                const std::vector<float>& weights, double fps) {
  const PoseFeatures features =
      PoseFeatures::FromRows(rows, frame_count, joint_count, weights, {0});
  const double weight_sum = std::accumulate(weights.begin(), weights.end(), 0.0);
  const uint64_t h = HalfWindow(fps);
  std::vector<double> speeds(frame_count, 0.0);
  if (frame_count < 2 || weight_sum <= 0) return speeds;
  for (uint64_t t = 0; t < frame_count; ++t) {
    const uint64_t a = t >= h ? t - h : 0;
    const uint64_t b = std::min(frame_count - 1, t + h);
    const double half_chord = std::min(1.0, PoseDistance(features, a, b) / weight_sum / 2.0);
    const double degrees = 4.0 * std::asin(half_chord) * 180.0 / std::numbers::pi;
    speeds[t] = degrees * fps / static_cast<double>(b - a);
  }
  return speeds;
}

namespace {

// `near` widened by `margin` frames each side within its clip, sorted and joined where they
// touch: the stretches to look at.
std::vector<MotifInstance> Neighbourhoods(const FrameFileReader& archive,
                                          std::vector<MotifInstance> near, uint64_t margin) {
  for (MotifInstance& range : near) {
    const ClipInfo& clip = archive.clips()[archive.ClipOfFrame(range.start)];
    range.start = range.start - std::min(margin, range.start - clip.first_frame);
    range.end = std::min(clip.first_frame + clip.frame_count, range.end + margin);
  }
  std::sort(near.begin(), near.end(),
            [](const MotifInstance& a, const MotifInstance& b) { return a.start < b.start; });
  std::vector<MotifInstance> joined;
  for (const MotifInstance& range : near) {
    if (!joined.empty() && range.start <= joined.back().end &&
        archive.ClipOfFrame(range.start) == archive.ClipOfFrame(joined.back().start)) {
      joined.back().end = std::max(joined.back().end, range.end);
    } else {
      joined.push_back(range);
    }
  }
  return joined;
}

}  // namespace

Result<std::vector<MotifInstance>> FindPauses(const FrameFileReader& archive,
                                              const PauseOptions& options) {
  std::vector<MotifInstance> clips;
  for (const ClipInfo& clip : archive.clips()) {
    if (clip.frame_count > 0)
      clips.push_back({clip.first_frame, clip.first_frame + clip.frame_count});
  }
  return FindPausesNear(archive, options, std::move(clips));
}

namespace {

// What FindPausesNear needs to scan one neighbourhood.
struct PauseScan {
  const FrameFileReader& archive;
  const PauseOptions& options;
  std::vector<float> weights;
  uint64_t h = 0;           // the speed's half window, frames
  uint64_t min_frames = 0;  // the shortest pause, frames
};

// The pauses of `range` (inside one clip), ascending, into *pauses.
Status PausesInRange(const PauseScan& scan, const MotifInstance& range, std::vector<float>* rows,
                     std::vector<MotifInstance>* pauses) {
  const FrameFileReader& archive = scan.archive;
  const ClipInfo& clip = archive.clips()[archive.ClipOfFrame(range.start)];
  const uint64_t clip_end = clip.first_frame + clip.frame_count;
  uint64_t run_start = 0;
  bool in_run = false;
  for (uint64_t from = range.start; from < range.end; from += kChunkFrames) {
    const uint64_t count = std::min(kChunkFrames, range.end - from);
    // Read h frames either side (within the clip) so the chunk's speeds equal the clip's.
    const uint64_t read_from = from - std::min(scan.h, from - clip.first_frame);
    const uint64_t read_end = std::min(clip_end, from + count + scan.h);
    MOTIF_RETURN_IF_ERROR(archive.ReadFrames(read_from, read_end - read_from, rows));
    const std::vector<double> speeds = FrameSpeeds(rows->data(), read_end - read_from,
                                                   archive.layout().joint_count, scan.weights,
                                                   archive.fps());
    const std::vector<double> own(
        speeds.begin() + static_cast<ptrdiff_t>(from - read_from),
        speeds.begin() + static_cast<ptrdiff_t>(from - read_from + count));
    CollectRuns(own, from, count, scan.options.max_speed, scan.min_frames, &run_start, &in_run,
                pauses);
  }
  if (in_run && range.end - run_start >= scan.min_frames) pauses->push_back({run_start, range.end});
  return Status::Ok();
}

}  // namespace

Result<std::vector<MotifInstance>> FindPausesNear(const FrameFileReader& archive,
                                                  const PauseOptions& options,
                                                  std::vector<MotifInstance> near, int threads) {
  MOTIF_RETURN_IF_ERROR(ValidatePauseOptions(options));
  std::vector<MotifInstance> pauses;
  if (options.max_speed == 0 || near.empty()) return pauses;
  for (const MotifInstance& range : near) {
    if (range.end <= range.start || range.end > archive.frame_count()) {
      return Status::InvalidArgument("[" + std::to_string(range.start) + ", " +
                                     std::to_string(range.end) +
                                     ") is not a frame range of the archive");
    }
  }
  PauseScan scan{archive, options, {}, HalfWindow(archive.fps()), 1};
  MOTIF_ASSIGN_OR_RETURN(scan.weights, LoadDistanceWeights(archive.skeleton(), ""));
  scan.min_frames = std::max<uint64_t>(
      1, static_cast<uint64_t>(std::lround(options.min_seconds * archive.fps())));
  const std::vector<MotifInstance> ranges =
      Neighbourhoods(archive, std::move(near), scan.min_frames);
  // Each neighbourhood scanned on its own (in parallel unless threads is 1), then joined in order.
  std::vector<std::vector<MotifInstance>> found(ranges.size());
  std::vector<Status> statuses(ranges.size());
  auto scan_all = [&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, ranges.size()), [&](const auto& block) {
      std::vector<float> rows;
      for (size_t idx = block.begin(); idx != block.end(); ++idx) {
        statuses[idx] = PausesInRange(scan, ranges[idx], &rows, &found[idx]);
      }
    });
  };
  if (threads == 1) {
    std::vector<float> rows;
    for (size_t idx = 0; idx < ranges.size(); ++idx) {
      MOTIF_RETURN_IF_ERROR(PausesInRange(scan, ranges[idx], &rows, &found[idx]));
    }
  } else if (threads > 0) {
    tbb::task_arena(threads).execute(scan_all);
  } else {
    scan_all();
  }
  for (size_t idx = 0; idx < ranges.size(); ++idx) {
    MOTIF_RETURN_IF_ERROR(statuses[idx]);
    pauses.insert(pauses.end(), found[idx].begin(), found[idx].end());
  }
  return pauses;
}

}  // namespace motif
