#include "engine/synth/motif_template.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/synth/synth_random.h"

namespace motif {
namespace {

constexpr int kWavesPerDof = 3;

enum class BodyPart { kRoot, kLegs, kLeftArm, kRightArm, kTorso, kHead, kCount };

BodyPart PartOf(const std::string& joint_name) {
  if (joint_name == "root") return BodyPart::kRoot;
  for (const char* leg : {"femur", "tibia", "foot", "toes"}) {
    if (joint_name.find(leg) != std::string::npos) return BodyPart::kLegs;
  }
  for (const char* torso : {"lowerback", "upperback", "thorax"}) {
    if (joint_name == torso) return BodyPart::kTorso;
  }
  for (const char* head : {"lowerneck", "upperneck", "head"}) {
    if (joint_name == head) return BodyPart::kHead;
  }
  return joint_name[0] == 'l' ? BodyPart::kLeftArm : BodyPart::kRightArm;
}

constexpr int kPartCount = static_cast<int>(BodyPart::kCount);

// Which body parts move a lot in this motif; at least two, one of them an arm. With an activity
// (`moving`) the legs and the root are the activity's.
struct ActiveParts {
  bool active[kPartCount] = {};
  bool operator[](BodyPart part) const { return active[static_cast<int>(part)]; }
};

ActiveParts DrawActiveParts(bool moving, SynthRandom* random) {
  ActiveParts parts;
  bool* active = parts.active;
  const double chance[] = {0.5, 0.4, 0.75, 0.75, 0.6, 0.5};
  int active_count = 0;
  for (int part = 0; part < kPartCount; ++part) {
    active[part] = random->Bernoulli(chance[part]);
    if (moving &&
        (part == static_cast<int>(BodyPart::kLegs) || part == static_cast<int>(BodyPart::kRoot))) {
      active[part] = false;  // the activity moves the legs and the root
    }
    active_count += active[part];
  }
  if (!active[static_cast<int>(BodyPart::kLeftArm)] &&
      !active[static_cast<int>(BodyPart::kRightArm)]) {
    active[static_cast<int>(random->Bernoulli(0.5) ? BodyPart::kLeftArm : BodyPart::kRightArm)] =
        true;
    ++active_count;
  }
  if (active_count < 2) active[static_cast<int>(BodyPart::kTorso)] = true;
  return parts;
}

// Active legs: one leg stands (small changes), the other moves mostly forward and back (a raised
// knee, a step, a kick), the knee bending more as the hip flexes (*hip_flexion: the free leg's,
// degrees, set by its femur before its tibia is drawn).
double DrawLegOffset(const BodyDof& dof, const std::string& joint_name, char free_leg,
                     double* hip_flexion, SynthRandom* random) {
  const bool free = joint_name[0] == free_leg;
  const bool sagittal = dof.axis == Axis::kX;
  double offset = 0;
  if (joint_name.find("femur") != std::string::npos && sagittal) {
    offset = free ? random->Normal(-15, 25) : random->Normal(0, 6);
    if (free) *hip_flexion = std::max(0.0, -offset);
  } else if (joint_name.find("tibia") != std::string::npos) {
    offset = free ? std::abs(random->Normal(0, 30)) + 0.6 * *hip_flexion
                  : std::abs(random->Normal(0, 8));
  } else {
    offset = random->Normal(0, free ? (sagittal ? 12 : 8) : 4);
  }
  return offset;
}

// An active arm, torso or head degree of freedom.
double DrawUpperBodyOffset(const BodyDof& dof, const std::string& joint_name, SynthRandom* random) {
  // Distal joints (wrists, hands, fingers) move less than shoulders and elbows.
  const bool distal = joint_name.find("wrist") != std::string::npos ||
                      joint_name.find("hand") != std::string::npos ||
                      joint_name.find("fingers") != std::string::npos ||
                      joint_name.find("thumb") != std::string::npos;
  double offset =
      random->Normal(0, std::min(distal ? 20.0 : 35.0, 0.22 * (dof.hi_deg - dof.lo_deg)));
  // One-sided joints (elbows, fingers) bend their own way.
  if (dof.lo_deg >= -10) offset = std::abs(offset);
  return offset;
}

// What every key of a motif shares, drawn once.
struct MotifKeyStyle {
  ActiveParts active;
  bool moving = false;                 // on top of an activity (keys are offsets from it)
  const ActivitySpec* base = nullptr;  // else keys are offsets from its mean pose
  double forward_base = 0;             // the root's forward speed, without an activity
  bool turning = false;
  char free_leg = 'l';
};

// One key: every degree of freedom's offset, and without an activity the root's speeds.
void DrawMotifKey(const CmuBodyModel& body, const MotifKeyStyle& style, SynthRandom* random,
                  double* key) {
  double hip_flexion = 0;  // of the free leg at this key, degrees
  for (size_t dof_idx = 0; dof_idx < body.dof_count(); ++dof_idx) {
    const BodyDof& dof = body.dof(dof_idx);
    const std::string& joint_name = body.skeleton().joint(dof.joint).name;
    const BodyPart part = PartOf(joint_name);
    double offset = 0;
    if (!style.active[part]) {
      offset = random->Normal(0, 3);
    } else if (part == BodyPart::kLegs) {
      offset = DrawLegOffset(dof, joint_name, style.free_leg, &hip_flexion, random);
    } else {
      offset = DrawUpperBodyOffset(dof, joint_name, random);
    }
    key[dof_idx] = (style.moving ? 0.0 : style.base->mean[dof_idx]) + offset;
  }
  if (!style.moving) {
    key[body.heading_rate_param()] = random->Normal(0, style.turning ? 40 : 10);
    key[body.forward_speed_param()] = style.forward_base + random->Normal(0, 2);
    key[body.side_speed_param()] = random->Normal(0, 3);
  }
}

// Catmull-Rom tangents of the keys (zero at the first and last key).
std::vector<double> KeyTangents(const std::vector<double>& keys, size_t key_count, size_t params) {
  std::vector<double> tangents(key_count * params, 0.0);
  for (size_t key_idx = 1; key_idx + 1 < key_count; ++key_idx) {
    for (size_t param = 0; param < params; ++param) {
      tangents[key_idx * params + param] =
          0.5 * (keys[(key_idx + 1) * params + param] - keys[(key_idx - 1) * params + param]);
    }
  }
  return tangents;
}

}  // namespace

MotifTemplate MotifTemplate::Create(const ActivityLibrary& library, uint64_t seed, uint64_t frames,
                                    double fps) {
  const CmuBodyModel& body = CmuBodyModel::Get();
  SynthRandom random(seed);
  MotifTemplate motif;
  motif.frames_ = frames;
  motif.fps_ = fps;
  motif.param_count_ = body.param_count();
  const double seconds = static_cast<double>(frames) / fps;
  motif.key_count_ =
      static_cast<size_t>(std::max(2.0, std::round(seconds * random.Uniform(1.0, 1.8)))) + 1;
  motif.key_spacing_ = static_cast<double>(frames - 1) / static_cast<double>(motif.key_count_ - 1);

  const ActivitySpec& base = library.activity(random.UniformInt(0, library.size() - 1));
  motif.moving_ = random.Bernoulli(0.5);
  if (motif.moving_) {
    motif.activity_ = base;
    motif.activity_offset_s_ = random.Uniform(0, 1.0 / base.frequency_hz);
  }
  // The draws in this order: the parts, the speed, turning, the free leg, then key by key.
  MotifKeyStyle style;
  style.active = DrawActiveParts(motif.moving_, &random);
  style.moving = motif.moving_;
  style.base = &base;
  style.forward_base = random.Uniform(-3, 10);
  style.turning = random.Bernoulli(0.5);
  style.free_leg = random.Bernoulli(0.5) ? 'l' : 'r';

  const size_t params = motif.param_count_;
  motif.keys_.assign(motif.key_count_ * params, 0.0);
  for (size_t key_idx = 0; key_idx < motif.key_count_; ++key_idx) {
    DrawMotifKey(body, style, &random, &motif.keys_[key_idx * params]);
  }
  motif.tangents_ = KeyTangents(motif.keys_, motif.key_count_, params);
  return motif;
}

void MotifTemplate::Evaluate(double motif_time, double* params) const {
  if (moving_) {
    activity_.Evaluate(motif_time / fps_ + activity_offset_s_, params);
  } else {
    std::fill(params, params + param_count_, 0.0);
  }
  const double clamped = std::clamp(motif_time, 0.0, static_cast<double>(frames_ - 1));
  const double position = clamped / key_spacing_;
  const size_t key_idx = std::min(static_cast<size_t>(position), key_count_ - 2);
  const double s = std::clamp(position - static_cast<double>(key_idx), 0.0, 1.0);
  const double s2 = s * s;
  const double s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1;
  const double h10 = s3 - 2 * s2 + s;
  const double h01 = -2 * s3 + 3 * s2;
  const double h11 = s3 - s2;
  const double* p0 = &keys_[key_idx * param_count_];
  const double* p1 = p0 + param_count_;
  const double* m0 = &tangents_[key_idx * param_count_];
  const double* m1 = m0 + param_count_;
  for (size_t param = 0; param < param_count_; ++param) {
    params[param] += h00 * p0[param] + h10 * m0[param] + h01 * p1[param] + h11 * m1[param];
  }
}

SmoothNoise::SmoothNoise(uint64_t seed, size_t dof_count, double sigma_degrees)
    : dof_count_(dof_count) {
  SynthRandom random(seed);
  // A sum of k sinusoids of amplitude a with independent phases has variance k a^2 / 2.
  const double amplitude = sigma_degrees * std::sqrt(2.0 / kWavesPerDof);
  waves_.reserve(dof_count * kWavesPerDof);
  for (size_t wave_idx = 0; wave_idx < dof_count * kWavesPerDof; ++wave_idx) {
    const double hz = random.Uniform(0.3, 2.0);
    waves_.push_back({amplitude, 2 * kPi * hz, random.Uniform(0, 2 * kPi)});
  }
}

void SmoothNoise::Add(double time_s, double* params) const {
  if (waves_.empty() || waves_[0].amplitude == 0) return;
  for (size_t dof_idx = 0; dof_idx < dof_count_; ++dof_idx) {
    const Wave* wave = &waves_[dof_idx * kWavesPerDof];
    double sum = 0;
    for (int idx = 0; idx < kWavesPerDof; ++idx) {
      sum += wave[idx].amplitude * std::sin(wave[idx].omega * time_s + wave[idx].phase);
    }
    params[dof_idx] += sum;
  }
}

}  // namespace motif
