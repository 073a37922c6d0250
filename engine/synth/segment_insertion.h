// Planting a real segment into real takes: the paper's check (Meng et al. 2008), in which one
// segment of a take is inserted several times, at different speeds, into other takes, and the
// miner must find every copy as one motif. Used by tests/engine/cluster/planted_motifs_test.cc
// and bench/studies/inserted_copies_check.cc.
// Thread-safety: pure functions.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "formats/motion/take.h"

namespace motif {

// A stretch of motion cut from a take: per frame, every joint's rotation and the root position.
struct Segment {
  std::vector<Eigen::Quaterniond> rotations;  // frame-major
  std::vector<Eigen::Vector3d> root_positions;
  size_t frame_count() const { return root_positions.size(); }
};

// The segment [start, start + frames) of `source` played through the time map `source_time`
// (output frame k -> fractional source frame, from 0 to frames - 1), `out_frames` long:
// rotations by slerp, root positions linearly. Needs start + frames <= source frames, frames >= 2.
Segment WarpSegment(const Take& source, size_t start, size_t frames, size_t out_frames,
                    const std::function<double(size_t)>& source_time);

// Every joint of `segment` turned by a small rotation that varies smoothly along it: a random
// rotation vector (each component normal with `degrees` standard deviation) every `spacing`
// frames, interpolated linearly between them. Deterministic for a seed.
void AddSmoothNoise(Segment* segment, double degrees, size_t spacing, uint64_t seed);

// `host` with `segment` inserted before its frame `at`. The segment's root path is moved to
// start where the host is at `at` (horizontally; heights kept), and the rest of the host to
// start where the segment ends, so the root does not jump.
Take InsertSegment(const Take& host, size_t at, const Segment& segment);

}  // namespace motif
