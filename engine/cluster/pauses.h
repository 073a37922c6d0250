// Pauses: stretches in which the body is still. A path that matches one movement with another
// often runs on through a held pose after it (a held pose matches a held pose), but a person
// names the movement and not "kick, then stand": so each instance is trimmed to its movement, its
// still head and tail going (instance_builder.h, MovingSpan). Pauses inside an instance stay: a
// planted motif that holds a pose midway was found as halves when cut there. Measured on the
// labelled takes and the synthetic archive in docs/design/motif_quality.md, section 8.
//
// Speed at frame t of a clip: the per-joint rotation angle θ of the pose distance between frames
// t − h and t + h (h = 25 ms, clamped to the clip), D = W · 2 sin(θ/4) with W the sum of the
// skeleton's default joint weights, divided by the time between the two frames: degrees per
// second, a mean over the weighted joints. A pause is a run of at least min_seconds of frames
// slower than max_speed.
// Thread-safety: pure function; the reader may be shared.
#pragma once

#include <vector>

#include "common/status.h"
#include "engine/cluster/motif_instance.h"
#include "formats/frame_file/frame_file_reader.h"
#include "motifmine/defaults.h"

namespace motif {

struct PauseOptions {
  double max_speed =
      motifmine::defaults::kPauseSpeed;  // degrees per second, mean over the weighted joints
  double min_seconds = motifmine::defaults::kPauseSeconds;  // the shortest pause
};

// InvalidArgument unless max_speed >= 0 and min_seconds > 0, both finite.
Status ValidatePauseOptions(const PauseOptions& options);

// The archive's pauses as global frame ranges, ascending, none spanning two clips. max_speed 0
// finds none (and reads nothing). Errors of the reader pass through.
Result<std::vector<MotifInstance>> FindPauses(const FrameFileReader& archive,
                                              const PauseOptions& options);

// The pauses that overlap the ranges `near` (each inside one clip), as far as they reach within
// min_seconds of them: only those frames are read (at 10^6 frames the instances cover a few per
// cent of the archive, and reading all of it cost 3.7 s). Trimming an instance of `near` at
// these gives what the whole archive's pauses give: a pause at least min_seconds long that
// overlaps the instance shows at least min_seconds of itself within that margin.
// The stretches are scanned in parallel unless threads is 1 (0: all cores); the result does not
// depend on it. InvalidArgument for a range outside the archive.
Result<std::vector<MotifInstance>> FindPausesNear(const FrameFileReader& archive,
                                                  const PauseOptions& options,
                                                  std::vector<MotifInstance> near,
                                                  int threads = 1);

// The speed of each of `frame_count` frames in `rows` (one clip's consecutive frames in
// FrameLayout order; tests): degrees per second at `fps`, as above.
std::vector<double> FrameSpeeds(const float* rows, uint64_t frame_count, uint32_t joint_count,
                                const std::vector<float>& weights, double fps);

}  // namespace motif
