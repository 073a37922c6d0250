#include "engine/synth/activity_library.h"

#include <cmath>
#include <string_view>
#include <utility>

#include "common/status.h"

namespace motif {
namespace {

constexpr Axis kX = Axis::kX;
constexpr Axis kY = Axis::kY;
constexpr Axis kZ = Axis::kZ;
constexpr double kTwoPi = 2.0 * kPi;

// Writes activities DOF by DOF, by joint name, with mirrored helpers for the limbs (a left-side
// value and its mirror image on the right, optionally shifted by half a cycle for gaits).
class ActivityBuilder {
 public:
  ActivityBuilder(std::string name, double frequency_hz) : body_(CmuBodyModel::Get()) {
    spec_.name = std::move(name);
    spec_.frequency_hz = frequency_hz;
    spec_.mean.assign(body_.param_count(), 0.0);
    StandingPose();
  }

  int Dof(std::string_view joint, Axis axis) const {
    const int dof_idx = body_.FindDof(joint, axis);
    MOTIF_CHECK(dof_idx >= 0);
    return dof_idx;
  }
  int Mirror(int dof_idx, double* sign) const {
    const int mirrored = body_.MirrorDof(dof_idx, sign);
    MOTIF_CHECK(mirrored >= 0);
    return mirrored;
  }

  void Mean(std::string_view joint, Axis axis, double degrees) {
    spec_.mean[Dof(joint, axis)] = degrees;
  }
  void MeanSym(std::string_view left_joint, Axis axis, double degrees) {
    const int dof_idx = Dof(left_joint, axis);
    double sign = 1;
    const int mirrored = Mirror(dof_idx, &sign);
    spec_.mean[dof_idx] = degrees;
    spec_.mean[mirrored] = sign * degrees;
  }
  void Wave(std::string_view joint, Axis axis, double amplitude, double rate, double peak,
            WaveShape shape = WaveShape::kCosine) {
    spec_.terms.push_back({static_cast<uint32_t>(Dof(joint, axis)), shape, amplitude, rate, peak});
  }
  // The left joint's wave and its mirror on the right, `right_shift` cycles later.
  void WaveSym(std::string_view left_joint, Axis axis, double amplitude, double rate, double peak,
               double right_shift, WaveShape shape = WaveShape::kCosine) {
    const int dof_idx = Dof(left_joint, axis);
    double sign = 1;
    const int mirrored = Mirror(dof_idx, &sign);
    spec_.terms.push_back({static_cast<uint32_t>(dof_idx), shape, amplitude, rate, peak});
    spec_.terms.push_back(
        {static_cast<uint32_t>(mirrored), shape, sign * amplitude, rate, peak + right_shift});
  }
  void ParamMean(size_t param, double value) { spec_.mean[param] = value; }
  void ParamWave(size_t param, double amplitude, double rate, double peak,
                 WaveShape shape = WaveShape::kCosine) {
    spec_.terms.push_back({static_cast<uint32_t>(param), shape, amplitude, rate, peak});
  }

  size_t heading() const { return body_.heading_rate_param(); }
  size_t forward() const { return body_.forward_speed_param(); }
  size_t side() const { return body_.side_speed_param(); }
  size_t jump() const { return body_.jump_param(); }
  double frequency() const { return spec_.frequency_hz; }

  ActivitySpec Build() { return std::move(spec_); }

 private:
  // A relaxed standing pose (angles in the ASF bone frames, close to CMU subjects' averages):
  // legs vertical, arms hanging with slightly bent elbows, the head level.
  void StandingPose() {
    Mean("root", kX, 5);
    Mean("lowerneck", kX, -12);
    Mean("upperneck", kX, 30);
    Mean("head", kX, 12);
    MeanSym("lclavicle", kY, -5);
    MeanSym("lclavicle", kZ, 5);
    MeanSym("lhumerus", kX, -28);
    MeanSym("lhumerus", kY, 5);
    MeanSym("lhumerus", kZ, 80);
    MeanSym("lradius", kX, 20);
    Mean("lwrist", kY, -10);
    Mean("rwrist", kY, -10);
    MeanSym("lfingers", kX, 15);
    MeanSym("lthumb", kX, 10);
    MeanSym("lthumb", kZ, 10);
    MeanSym("lfemur", kX, -6);
    MeanSym("lfemur", kZ, -20);
    MeanSym("ltibia", kX, 6);
    MeanSym("lfoot", kX, -8);
    MeanSym("lfoot", kZ, 5);
    MeanSym("ltoes", kX, -5);
  }

  const CmuBodyModel& body_;
  ActivitySpec spec_;
};

// "l..." or "r..." for a limb joint of the chosen side.
std::string Side(const char* left_joint, bool right) {
  std::string name(left_joint);
  if (right) name[0] = 'r';
  return name;
}

// Adds the left/right mirrored wave for the chosen side only (sign handled by the mirror).
void WaveSide(ActivityBuilder* builder, const char* left_joint, Axis axis, double amplitude,
              double rate, double peak, bool right, WaveShape shape = WaveShape::kCosine) {
  double sign = 1;
  builder->Mirror(builder->Dof(left_joint, axis), &sign);
  builder->Wave(Side(left_joint, right), axis, right ? sign * amplitude : amplitude, rate, peak,
                shape);
}

void MeanSide(ActivityBuilder* builder, const char* left_joint, Axis axis, double degrees,
              bool right) {
  double sign = 1;
  builder->Mirror(builder->Dof(left_joint, axis), &sign);
  builder->Mean(Side(left_joint, right), axis, right ? sign * degrees : degrees);
}

ActivitySpec Walk(SynthRandom* random) {
  ActivityBuilder b("walk", random->Uniform(0.8, 1.0));
  b.MeanSym("lfemur", kX, -12);
  b.WaveSym("lfemur", kX, 22, 1, 0.5, 0.5);  // hip flexion (negative) peaks at cycle 0
  b.WaveSym("lfemur", kY, 4, 1, 0.0, 0.5);
  b.WaveSym("lfemur", kZ, 3, 1, 0.25, 0.5);
  b.MeanSym("ltibia", kX, 25);
  b.WaveSym("ltibia", kX, 24, 1, 0.85, 0.5);  // swing-phase knee flexion
  b.WaveSym("ltibia", kX, 7, 2, 0.1, 0.5);
  b.WaveSym("lfoot", kX, 10, 1, 0.6, 0.5);
  b.WaveSym("ltoes", kX, 8, 1, 0.1, 0.5);
  b.Mean("root", kX, 6);
  b.Wave("root", kX, 2, 2, 0.1);
  b.Wave("root", kY, 5, 1, 0.0);
  b.Wave("root", kZ, 3, 1, 0.25);
  b.Wave("lowerback", kY, -4, 1, 0.0);
  b.Wave("thorax", kY, -3, 1, 0.0);
  b.WaveSym("lhumerus", kX, 16, 1, 0.5, 0.5);  // arms swing against the opposite leg
  b.MeanSym("lradius", kX, 25);
  b.WaveSym("lradius", kX, 8, 1, 0.5, 0.5);
  const double speed = random->Uniform(22, 28) * b.frequency();  // stride length * cadence
  b.ParamMean(b.forward(), speed);
  b.ParamWave(b.forward(), 0.08 * speed, 2, 0.1);
  b.ParamWave(b.side(), 0.6, 1, 0.25);
  b.ParamMean(b.heading(), random->Uniform(-20, 20));
  b.ParamWave(b.heading(), random->Uniform(0, 15), 0.1, random->Uniform());
  return b.Build();
}

ActivitySpec Run(SynthRandom* random) {
  ActivityBuilder b("run", random->Uniform(1.25, 1.5));
  b.MeanSym("lfemur", kX, -20);
  b.WaveSym("lfemur", kX, 30, 1, 0.5, 0.5);
  b.WaveSym("lfemur", kZ, 4, 1, 0.25, 0.5);
  b.MeanSym("ltibia", kX, 55);
  b.WaveSym("ltibia", kX, 45, 1, 0.8, 0.5);
  b.WaveSym("ltibia", kX, 10, 2, 0.15, 0.5);
  b.MeanSym("lfoot", kX, 0);
  b.WaveSym("lfoot", kX, 20, 1, 0.6, 0.5);
  b.WaveSym("ltoes", kX, 10, 1, 0.1, 0.5);
  b.Mean("root", kX, 10);
  b.Wave("root", kX, 3, 2, 0.1);
  b.Wave("root", kY, 6, 1, 0.0);
  b.Wave("root", kZ, 4, 1, 0.25);
  b.Mean("lowerback", kX, 10);
  b.Wave("lowerback", kY, -5, 1, 0.0);
  b.MeanSym("lhumerus", kX, -20);
  b.MeanSym("lhumerus", kZ, 70);
  b.WaveSym("lhumerus", kX, 25, 1, 0.5, 0.5);
  b.MeanSym("lradius", kX, 95);
  b.WaveSym("lradius", kX, 12, 1, 0.5, 0.5);
  const double speed = random->Uniform(32, 40) * b.frequency();
  b.ParamMean(b.forward(), speed);
  b.ParamWave(b.forward(), 0.06 * speed, 2, 0.1);
  b.ParamWave(b.side(), 1.0, 1, 0.25);
  b.ParamWave(b.jump(), 0.8, 2, 0.45, WaveShape::kPulse);  // flight phases
  b.ParamMean(b.heading(), random->Uniform(-15, 15));
  b.ParamWave(b.heading(), random->Uniform(0, 10), 0.1, random->Uniform());
  return b.Build();
}

ActivitySpec SideStep(SynthRandom* random) {
  ActivityBuilder b("sidestep", random->Uniform(0.6, 0.9));
  b.MeanSym("lfemur", kX, -12);
  b.MeanSym("ltibia", kX, 15);
  b.Mean("root", kX, 8);
  b.Wave("lfemur", kZ, 10, 1, 0.0);
  b.Wave("rfemur", kZ, -8, 1, 0.35);
  b.WaveSym("ltibia", kX, 12, 1, 0.0, 0.35);
  b.Wave("root", kZ, 4, 1, 0.1);
  b.WaveSym("lhumerus", kZ, -8, 1, 0.0, 0.35);
  b.MeanSym("lradius", kX, 40);
  const double direction = random->Bernoulli(0.5) ? 1.0 : -1.0;
  const double speed = direction * random->Uniform(10, 16) * b.frequency() / 0.75;
  b.ParamMean(b.side(), speed);
  b.ParamWave(b.side(), 0.3 * speed, 1, 0.1);
  b.ParamMean(b.heading(), random->Uniform(-8, 8));
  return b.Build();
}

ActivitySpec Idle(SynthRandom* random) {
  ActivityBuilder b("idle", random->Uniform(0.15, 0.3));
  b.Wave("root", kZ, 3, 1, 0.0);
  b.WaveSym("lfemur", kZ, 3, 1, 0.0, 0.0);
  b.WaveSym("ltibia", kX, 4, 1, 0.0, 0.5);
  b.ParamWave(b.side(), 0.8, 1, 0.25);
  b.Wave("head", kY, 15, 1.7, random->Uniform());
  b.Wave("upperneck", kX, 6, 2.3, random->Uniform());
  b.WaveSym("lhumerus", kX, 6, 1.3, random->Uniform(), 0.3);
  b.WaveSym("lradius", kX, 10, 0.8, random->Uniform(), 0.2);
  b.Wave("lowerback", kY, 5, 1, 0.3);
  b.Wave("thorax", kX, 3, 1, 0.6);
  b.ParamWave(b.heading(), random->Uniform(0, 10), 0.5, random->Uniform());
  return b.Build();
}

ActivitySpec ArmWave(SynthRandom* random) {
  ActivityBuilder b("wave", random->Uniform(0.5, 1.1));
  const int mode = static_cast<int>(random->UniformInt(0, 2));  // left, right, both
  for (int side = 0; side < 2; ++side) {
    if (mode != 2 && mode != side) continue;
    const bool right = side == 1;
    MeanSide(&b, "lhumerus", kZ, random->Uniform(-30, 30), right);
    MeanSide(&b, "lhumerus", kX, random->Uniform(0, 50), right);
    WaveSide(&b, "lhumerus", kZ, 25, 1, 0.0, right);
    MeanSide(&b, "lradius", kX, 70, right);
    WaveSide(&b, "lradius", kX, 45, 1, 0.3, right);
    WaveSide(&b, "lhand", kX, 20, 2, 0.1, right);
    MeanSide(&b, "lclavicle", kZ, 10, right);
  }
  b.Wave("lowerback", kZ, 4, 1, 0.0);
  b.Wave("head", kY, 8, 1, 0.2);
  b.WaveSym("lfemur", kZ, 2, 1, 0.0, 0.0);
  b.ParamWave(b.side(), 0.5, 1, 0.25);
  return b.Build();
}

ActivitySpec Squat(SynthRandom* random) {
  ActivityBuilder b("squat", random->Uniform(0.25, 0.5));
  const double depth = random->Uniform(0.6, 1.0);
  // Peak 0.5 is standing, 0 the bottom of the squat.
  b.MeanSym("lfemur", kX, -6 - 32 * depth);
  b.WaveSym("lfemur", kX, 32 * depth, 1, 0.5, 0.0);
  b.MeanSym("ltibia", kX, 6 + 40 * depth);
  b.WaveSym("ltibia", kX, -40 * depth, 1, 0.5, 0.0);
  b.MeanSym("lfoot", kX, -5 - 15 * depth);
  b.WaveSym("lfoot", kX, 15 * depth, 1, 0.5, 0.0);
  b.Mean("root", kX, 4 + 13 * depth);
  b.Wave("root", kX, -13 * depth, 1, 0.5);
  b.Mean("lowerback", kX, 8 * depth);
  b.Wave("lowerback", kX, -8 * depth, 1, 0.5);
  b.MeanSym("lhumerus", kX, 10);
  b.WaveSym("lhumerus", kX, -35, 1, 0.5, 0.0);  // arms reach forward at the bottom
  b.Wave("head", kX, 5, 1, 0.0);
  return b.Build();
}

ActivitySpec Dance(SynthRandom* random) {
  ActivityBuilder b("dance", random->Uniform(0.8, 1.2));
  b.Wave("root", kY, 12, 1, 0.0);
  b.Wave("root", kZ, 6, 1, 0.25);
  b.Wave("root", kX, 4, 2, 0.0);
  b.MeanSym("lfemur", kX, -12);
  b.WaveSym("lfemur", kX, 12, 1, 0.5, 0.5);
  b.MeanSym("ltibia", kX, 20);
  b.WaveSym("ltibia", kX, 18, 1, 0.9, 0.5);
  b.WaveSym("lfoot", kX, 10, 1, 0.6, 0.5);
  b.MeanSym("lhumerus", kZ, 50);
  b.MeanSym("lhumerus", kX, 0);
  b.WaveSym("lhumerus", kZ, 30, 1, 0.0, random->Bernoulli(0.5) ? 0.5 : 0.0);
  b.WaveSym("lhumerus", kX, 25, 0.5, 0.1, 0.25);
  b.MeanSym("lradius", kX, 60);
  b.WaveSym("lradius", kX, 35, 1, 0.3, 0.5);
  b.Wave("lowerback", kZ, 8, 1, 0.25);
  b.Wave("upperback", kY, 6, 0.5, 0.0);
  b.Wave("head", kZ, 6, 1, 0.5);
  b.ParamMean(b.heading(), random->Uniform(-30, 30));
  b.ParamWave(b.heading(), random->Uniform(30, 90), 0.25, random->Uniform());
  b.ParamWave(b.jump(), 0.3, 2, 0.5, WaveShape::kPulse);
  b.ParamWave(b.forward(), 3, 0.5, 0.0);
  return b.Build();
}

ActivitySpec Boxing(SynthRandom* random) {
  ActivityBuilder b("boxing", random->Uniform(0.7, 1.2));
  b.Mean("root", kX, 8);
  b.Mean("root", kY, -15);  // bladed stance
  b.Mean("lowerback", kX, 8);
  b.MeanSym("lfemur", kX, -20);
  b.MeanSym("ltibia", kX, 25);
  b.MeanSym("lhumerus", kX, 5);
  b.MeanSym("lhumerus", kZ, 70);
  b.MeanSym("lradius", kX, 125);  // guard
  // Alternating punches: the elbow extends while the upper arm rises forward.
  b.WaveSym("lradius", kX, -100, 1, 0.0, 0.5, WaveShape::kPulse);
  b.WaveSym("lhumerus", kX, 40, 1, 0.0, 0.5, WaveShape::kPulse);
  b.WaveSym("lhumerus", kZ, -20, 1, 0.0, 0.5, WaveShape::kPulse);
  b.Wave("thorax", kY, 10, 1, 0.0);
  b.Wave("lowerback", kY, 6, 1, 0.0);
  b.WaveSym("ltibia", kX, 6, 2, 0.0, 0.0);
  b.ParamWave(b.jump(), 0.4, 2, 0.5, WaveShape::kPulse);  // bouncing on the toes
  b.ParamWave(b.side(), 3, 0.5, 0.0);
  b.ParamWave(b.forward(), 4, 0.5, 0.25);
  b.ParamWave(b.heading(), 20, 0.3, random->Uniform());
  return b.Build();
}

ActivitySpec Hop(SynthRandom* random) {
  ActivityBuilder b("hop", random->Uniform(1.2, 1.7));
  b.ParamWave(b.jump(), random->Uniform(1.5, 3.0), 1, 0.5, WaveShape::kPulse);  // flight
  b.MeanSym("ltibia", kX, 15);
  b.WaveSym("ltibia", kX, 45, 1, 0.0, 0.0, WaveShape::kPulse);  // crouch at landing
  b.MeanSym("lfemur", kX, -8);
  b.WaveSym("lfemur", kX, -35, 1, 0.0, 0.0, WaveShape::kPulse);
  b.WaveSym("lfoot", kX, -15, 1, 0.0, 0.0, WaveShape::kPulse);
  b.WaveSym("lfoot", kX, 15, 1, 0.5, 0.0);
  b.Wave("root", kX, 12, 1, 0.0, WaveShape::kPulse);
  b.WaveSym("lhumerus", kX, 30, 1, 0.45, 0.0);
  b.MeanSym("lradius", kX, 35);
  b.ParamMean(b.forward(), random->Uniform(0, 12));
  b.ParamMean(b.heading(), random->Uniform(-10, 10));
  return b.Build();
}

ActivitySpec Kick(SynthRandom* random) {
  ActivityBuilder b("kick", random->Uniform(0.35, 0.6));
  const bool right = random->Bernoulli(0.5);
  WaveSide(&b, "lfemur", kX, -random->Uniform(50, 80), 1, 0.5, right, WaveShape::kPulse);
  WaveSide(&b, "ltibia", kX, 60, 1, 0.42, right, WaveShape::kPulse);  // chamber, then extend
  WaveSide(&b, "lfoot", kX, 20, 1, 0.5, right, WaveShape::kPulse);
  MeanSide(&b, "ltibia", kX, 15, !right);  // the supporting leg
  MeanSide(&b, "lfemur", kX, -10, !right);
  b.Wave("lowerback", kX, -12, 1, 0.5, WaveShape::kPulse);
  b.Wave("root", kX, -8, 1, 0.5, WaveShape::kPulse);
  b.MeanSym("lhumerus", kZ, 55);
  b.MeanSym("lradius", kX, 90);
  WaveSide(&b, "lhumerus", kX, 30, 1, 0.5, !right, WaveShape::kPulse);
  b.ParamWave(b.forward(), 5, 1, 0.6, WaveShape::kPulse);
  b.ParamMean(b.heading(), random->Uniform(-5, 5));
  return b.Build();
}

ActivitySpec TurnInPlace(SynthRandom* random) {
  ActivityBuilder b("turn", random->Uniform(0.6, 0.9));
  const double direction = random->Bernoulli(0.5) ? 1.0 : -1.0;
  b.ParamMean(b.heading(), direction * random->Uniform(60, 120));
  b.MeanSym("lfemur", kX, -8);
  b.WaveSym("lfemur", kX, 8, 1, 0.5, 0.5);
  b.MeanSym("ltibia", kX, 12);
  b.WaveSym("ltibia", kX, 12, 1, 0.9, 0.5);
  b.WaveSym("lhumerus", kX, 6, 1, 0.5, 0.5);
  b.Wave("root", kY, 4, 1, 0.0);
  b.Wave("root", kZ, 2, 1, 0.25);
  b.Mean("upperneck", kY, direction * 8);  // looking into the turn
  return b.Build();
}

using ArchetypeFn = ActivitySpec (*)(SynthRandom*);
constexpr ArchetypeFn kArchetypes[] = {Walk,  Run,    SideStep, Idle, ArmWave,    Squat,
                                       Dance, Boxing, Hop,      Kick, TurnInPlace};

// Upper-body DOFs that may carry a personal "style" gesture.
bool IsUpperBody(const CmuBodyModel& body, size_t dof_idx) {
  const std::string& name = body.skeleton().joint(body.dof(dof_idx).joint).name;
  return name != "root" && name.find("femur") == std::string::npos &&
         name.find("tibia") == std::string::npos && name.find("foot") == std::string::npos &&
         name.find("toes") == std::string::npos && name.find("fingers") == std::string::npos &&
         name.find("thumb") == std::string::npos;
}

}  // namespace

void ActivitySpec::Evaluate(double time_s, double* params) const {
  for (size_t param = 0; param < mean.size(); ++param) params[param] = mean[param];
  const double cycles = frequency_hz * time_s;
  for (const ActivityTerm& term : terms) {
    const double c = std::cos(kTwoPi * (term.rate * cycles - term.peak));
    if (term.shape == WaveShape::kCosine) {
      params[term.param] += term.amplitude * c;
    } else {
      const double beat = 0.5 * (1.0 + c);
      params[term.param] += term.amplitude * beat * beat * beat;
    }
  }
}

size_t ActivityLibrary::ArchetypeCount() { return std::size(kArchetypes); }

ActivityLibrary ActivityLibrary::Create(uint64_t seed, size_t count) {
  const CmuBodyModel& body = CmuBodyModel::Get();
  ActivityLibrary library;
  for (size_t activity_idx = 0; activity_idx < count; ++activity_idx) {
    SynthRandom random(DeriveSeed(seed, SeedStream::kActivityLibrary, activity_idx));
    ActivitySpec spec = kArchetypes[activity_idx % std::size(kArchetypes)](&random);
    // This performer's variation: wave sizes and timing, a slightly different carriage of the
    // arms, torso and head, and a few personal gestures.
    for (ActivityTerm& term : spec.terms) {
      term.amplitude *= random.Uniform(0.75, 1.25);
      term.peak += random.Normal(0, 0.03);
    }
    for (size_t dof_idx = 0; dof_idx < body.dof_count(); ++dof_idx) {
      if (IsUpperBody(body, dof_idx)) spec.mean[dof_idx] += random.Normal(0, 3);
    }
    const int gestures = static_cast<int>(random.UniformInt(2, 4));
    for (int gesture_idx = 0; gesture_idx < gestures; ++gesture_idx) {
      size_t dof_idx = random.UniformInt(0, body.dof_count() - 1);
      while (!IsUpperBody(body, dof_idx)) dof_idx = random.UniformInt(0, body.dof_count() - 1);
      static constexpr double kRates[] = {0.5, 1.0, 2.0};
      spec.terms.push_back({static_cast<uint32_t>(dof_idx), WaveShape::kCosine,
                            random.Uniform(2, 8) * (random.Bernoulli(0.5) ? 1 : -1),
                            kRates[random.UniformInt(0, 2)], random.Uniform()});
    }
    library.activities_.push_back(std::move(spec));
  }
  return library;
}

ActivitySpec ActivityLibrary::Perturb(size_t activity_idx, SynthRandom* random) const {
  const CmuBodyModel& body = CmuBodyModel::Get();
  ActivitySpec spec = activities_[activity_idx];
  const double cadence = random->Uniform(0.92, 1.08);
  spec.frequency_hz *= cadence;
  const size_t forward = body.forward_speed_param();
  const size_t side = body.side_speed_param();
  for (ActivityTerm& term : spec.terms) {
    term.amplitude *= std::max(0.0, 1.0 + random->Normal(0, 0.1));
    term.peak += random->Normal(0, 0.02);
    if (term.param == forward || term.param == side) term.amplitude *= cadence;
  }
  spec.mean[forward] *= cadence;
  spec.mean[side] *= cadence;
  spec.mean[body.heading_rate_param()] += random->Normal(0, 6);
  for (size_t dof_idx = 0; dof_idx < body.dof_count(); ++dof_idx) {
    spec.mean[dof_idx] += random->Normal(0, 1.5);
  }
  // Slow drifts of posture, unrelated to the cycle.
  for (int drift_idx = 0; drift_idx < 4; ++drift_idx) {
    const size_t dof_idx = random->UniformInt(0, body.dof_count() - 1);
    const double drift_hz = random->Uniform(0.04, 0.15);
    spec.terms.push_back({static_cast<uint32_t>(dof_idx), WaveShape::kCosine, random->Uniform(1, 4),
                          drift_hz / spec.frequency_hz, random->Uniform()});
  }
  return spec;
}

}  // namespace motif
