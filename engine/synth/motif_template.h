// MotifTemplate: one planted motif of the procedural mode, a distinct movement `frames` long
// described in CmuBodyModel parameters. It is a smooth key-pose curve: a few random key poses
// (about 1 to 1.8 per second) joined by a Catmull-Rom spline whose tangents are zero at the two
// ends, so the motif starts and ends at rest and holding its end poses is smooth. Some body
// parts are "active" in a motif (large excursions within their joint limits), the others keep
// near the base pose. Half of the motifs happen on top of a library activity (a gesture while
// walking, dancing, ...): the activity's legs and root motion carry on under the key-pose
// offsets; the others are performed on the spot, with their own root tilt, turn and drift.
// SmoothNoise: the small smooth per-DOF noise an instance adds to its motif (a few slow
// sinusoids per DOF whose sum has the requested standard deviation).
// Thread-safety: immutable once built; const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/synth/activity_library.h"

namespace motif {

class MotifTemplate {
 public:
  // Motif of `frames` (>= 2) frames at `fps`, drawn from `seed`.
  static MotifTemplate Create(const ActivityLibrary& library, uint64_t seed, uint64_t frames,
                              double fps);

  uint64_t frames() const { return frames_; }
  bool moving() const { return moving_; }
  // Parameters at motif time `motif_time` (motif frames; the key poses hold outside
  // [0, frames - 1], an underlying activity carries on).
  void Evaluate(double motif_time, double* params) const;

 private:
  uint64_t frames_ = 0;
  double fps_ = 120;
  size_t param_count_ = 0;
  size_t key_count_ = 0;
  double key_spacing_ = 1;        // motif frames between keys
  std::vector<double> keys_;      // key_count_ * param_count_
  std::vector<double> tangents_;  // per key, in key-interval units
  bool moving_ = false;
  ActivitySpec activity_;  // when moving_
  double activity_offset_s_ = 0;
};

class SmoothNoise {
 public:
  // Noise on the DOF angles (CmuBodyModel::dof_count() of them), standard deviation
  // `sigma_degrees` each, frequencies 0.3 to 2 Hz.
  SmoothNoise(uint64_t seed, size_t dof_count, double sigma_degrees);
  // Adds the noise at time `time_s` to params[0 .. dof_count).
  void Add(double time_s, double* params) const;

 private:
  struct Wave {
    double amplitude;
    double omega;  // radians per second
    double phase;
  };
  size_t dof_count_ = 0;
  std::vector<Wave> waves_;  // kWavesPerDof per DOF
};

}  // namespace motif
