// ActivityLibrary: the repertoire the procedural background is made of. An activity is a
// periodic movement of the whole body (walk, run, side-step, idle sway, arm waving, squats,
// dance, boxing, hopping, kicks, turning on the spot) written as a mean pose plus a set of
// per-DOF waves at multiples of a base frequency, with root motion (forward and side speed, turn
// rate, jumps) consistent with it: a walk moves forward at stride length * cadence, a squat stays
// put and lowers the root through the legs' bend. A library of `count` activities is drawn from
// the built-in archetypes with seeded variations (amplitudes, phases, style gestures, cadence),
// and every background segment is a further perturbed copy of one library entry. A periodic
// activity repeats itself cycle after cycle, so the procedural generator adds each segment its
// own smooth variation (SynthOptions::background_variation_degrees): without it the background
// repeats within eps for longer than lambda and the planted motifs are not the only repeats.
// Thread-safety: a built library is immutable; const methods are safe from many threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/synth/cmu_body_model.h"
#include "engine/synth/synth_random.h"

namespace motif {

enum class WaveShape : uint8_t {
  kCosine,  // amplitude * cos(x)
  kPulse,   // amplitude * ((1 + cos x) / 2)^3: a smooth, peaked beat (punches, kicks, hops)
};

// One wave on one parameter: amplitude * shape(2 pi (rate * f * t - peak)), f the activity's
// frequency, t seconds: it peaks at cycle position `peak`.
struct ActivityTerm {
  uint32_t param = 0;
  WaveShape shape = WaveShape::kCosine;
  double amplitude = 0;  // degrees, or length units (per second) for root channels
  double rate = 1;       // cycles per activity cycle
  double peak = 0;       // cycles
};

struct ActivitySpec {
  std::string name;          // archetype name, e.g. "walk"
  double frequency_hz = 1;   // base cycle frequency
  std::vector<double> mean;  // CmuBodyModel::param_count() values
  std::vector<ActivityTerm> terms;

  // Writes the parameters at time `time_s` into `params` (param_count values).
  void Evaluate(double time_s, double* params) const;
};

class ActivityLibrary {
 public:
  // `count` (>= 1) activities; the archetypes are used in turn, so every one appears once
  // `count` reaches their number.
  static ActivityLibrary Create(uint64_t seed, size_t count);
  static size_t ArchetypeCount();

  size_t size() const { return activities_.size(); }
  const ActivitySpec& activity(size_t activity_idx) const { return activities_[activity_idx]; }

  // A copy of activity `activity_idx` perturbed for one segment: amplitudes (+-10 %), peaks,
  // cadence (+-8 %, with the speeds that go with it), mean pose, turn rate, plus slow drifts.
  ActivitySpec Perturb(size_t activity_idx, SynthRandom* random) const;

 private:
  std::vector<ActivitySpec> activities_;
};

}  // namespace motif
