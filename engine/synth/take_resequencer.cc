#include "engine/synth/take_resequencer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/synth/synth_random.h"
#include "formats/motion/quaternion_math.h"
#include "formats/motion/resample.h"

namespace motif {
namespace {

constexpr int kNoiseWavesPerAxis = 2;
constexpr int kDrawAttempts = 24;
// A joint turning further than this between two frames (1/120 s) is a capture glitch.
constexpr double kGlitchDegrees = 60;

Status InvalidSources(const std::string& message) {
  return Status::InvalidArgument("synth sources: " + message);
}

std::string TakeLabel(const Take& take) {
  return "'" + (take.source_path.empty() ? take.name : take.source_path) + "'";
}

// Slerp from a to b along the arc given by their signs (no flip to the shorter arc).
Eigen::Quaterniond SignedSlerp(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b,
                               double weight) {
  const double dot = std::clamp(a.dot(b), -1.0, 1.0);
  const double angle = std::acos(dot);
  const double sine = std::sin(angle);
  double wa = 1.0 - weight;
  double wb = weight;
  if (sine > 1e-6) {
    wa = std::sin((1.0 - weight) * angle) / sine;
    wb = std::sin(weight * angle) / sine;
  }
  Eigen::Quaterniond result;
  result.coeffs() = wa * a.coeffs() + wb * b.coeffs();
  return result.normalized();
}

// Flips each rotation to the side of its reference: keeps a track's signs continuous in time.
void AlignSigns(const std::vector<Eigen::Quaterniond>& reference,
                std::vector<Eigen::Quaterniond>* rotations) {
  if (reference.size() != rotations->size()) return;
  for (size_t joint_idx = 0; joint_idx < rotations->size(); ++joint_idx) {
    (*rotations)[joint_idx] = AlignSign((*rotations)[joint_idx], reference[joint_idx]);
  }
}

}  // namespace

// One frame of motion ready to blend: local rotations (the root's without its heading) and the
// root's increments since the previous frame.
struct TakeResequencer::FrameMotion {
  std::vector<Eigen::Quaterniond> rotations;
  double heading_delta = 0;              // radians
  Eigen::Vector3d local_delta{0, 0, 0};  // displacement in the heading frame (y unused)
  double height = 0;

  // Moves toward `other` by `weight`. Rotations follow the arc between the two as signed (the
  // caller keeps each track's signs continuous in time and aligns a track to the other when a
  // blend starts), not the per-frame shortest arc, which can switch sides from one frame to the
  // next when two pieces hold a joint nearly opposite ways.
  void BlendToward(const FrameMotion& other, double weight) {
    for (size_t joint_idx = 0; joint_idx < rotations.size(); ++joint_idx) {
      rotations[joint_idx] = SignedSlerp(rotations[joint_idx], other.rotations[joint_idx], weight);
    }
    heading_delta += weight * (other.heading_delta - heading_delta);
    local_delta += weight * (other.local_delta - local_delta);
    height += weight * (other.height - height);
  }
};

// Smooth small rotations for every non-root joint: per axis a sum of slow sinusoids.
class TakeResequencer::RotationNoise {
 public:
  RotationNoise() = default;
  RotationNoise(uint64_t seed, size_t joint_count, double sigma_degrees) {
    SynthRandom random(seed);
    const double amplitude = sigma_degrees * (kPi / 180.0) * std::sqrt(2.0 / kNoiseWavesPerAxis);
    if (amplitude == 0) return;
    waves_.resize(joint_count * 3 * kNoiseWavesPerAxis);
    for (Wave& wave : waves_) {
      wave = {amplitude, 2 * kPi * random.Uniform(0.3, 2.0), random.Uniform(0, 2 * kPi)};
    }
  }
  void Apply(double time_s, std::vector<Eigen::Quaterniond>* rotations) const {
    if (waves_.empty()) return;
    for (size_t joint_idx = 1; joint_idx < rotations->size(); ++joint_idx) {
      Eigen::Vector3d angles;
      for (int axis = 0; axis < 3; ++axis) {
        const Wave* wave = &waves_[(joint_idx * 3 + axis) * kNoiseWavesPerAxis];
        double sum = 0;
        for (int idx = 0; idx < kNoiseWavesPerAxis; ++idx) {
          sum += wave[idx].amplitude * std::sin(wave[idx].omega * time_s + wave[idx].phase);
        }
        angles[axis] = sum;
      }
      const double angle = angles.norm();
      if (angle > 0) {
        (*rotations)[joint_idx] =
            (*rotations)[joint_idx] * Eigen::Quaterniond(Eigen::AngleAxisd(angle, angles / angle));
      }
    }
  }

 private:
  struct Wave {
    double amplitude;
    double omega;
    double phase;
  };
  std::vector<Wave> waves_;
};

struct TakeResequencer::SourceSegment {
  size_t take_idx = 0;
  double source_start = 0;  // source frame of the segment's first frame
  double rate = 1;          // source frames per output frame (1 / speed factor)
  int64_t start = 0;        // clip frame
  int64_t frames = 0;       // including the crossfade into the next segment
  int64_t crossfade = 0;
  RotationNoise noise;
};

Result<std::unique_ptr<TakeResequencer>> TakeResequencer::Create(const SynthOptions& options,
                                                                 std::vector<Take> sources,
                                                                 const SynthPlan& plan) {
  if (sources.empty()) return InvalidSources("no source takes to re-sequence");
  const Take& first = sources[0];
  if (first.joint_count() == 0)
    return InvalidSources("take " + TakeLabel(first) + " has no joints");
  uint64_t longest = 0;
  for (const Take& take : sources) {
    if (!take.skeleton.SameHierarchy(first.skeleton)) {
      return InvalidSources("take " + TakeLabel(take) + " (skeleton family '" +
                            take.skeleton.family() + "', " + std::to_string(take.joint_count()) +
                            " joints) does not have the skeleton of take " + TakeLabel(first) +
                            " (family '" + first.skeleton.family() + "', " +
                            std::to_string(first.joint_count()) +
                            " joints): mixed skeletons cannot be re-sequenced together");
    }
    if (!SameFrameRate(take.fps, options.fps)) {
      return InvalidSources("take " + TakeLabel(take) + " is at " + std::to_string(take.fps) +
                            " fps, the archive at " + std::to_string(options.fps) +
                            " fps: resample the sources first");
    }
    if (take.rotations.size() != take.frame_count() * take.joint_count()) {
      return InvalidSources("take " + TakeLabel(take) + " has " +
                            std::to_string(take.rotations.size()) + " rotations for " +
                            std::to_string(take.frame_count()) + " frames of " +
                            std::to_string(take.joint_count()) + " joints");
    }
    longest = std::max<uint64_t>(longest, take.frame_count());
  }
  uint64_t needed = std::max<uint64_t>(
      2, static_cast<uint64_t>(std::llround(options.segment_seconds_min * options.fps)));
  for (uint64_t motif_frames : plan.motif_frames()) needed = std::max(needed, motif_frames);
  if (longest < needed) {
    return InvalidSources("too short: the longest take has " + std::to_string(longest) +
                          " frames, fewer than the " + std::to_string(needed) +
                          " needed for a segment (segment_seconds_min) or a motif "
                          "(motif_seconds_max); give longer takes or lower those options");
  }
  return std::unique_ptr<TakeResequencer>(new TakeResequencer(options, std::move(sources), plan));
}

namespace {

// The root's heading at every frame of `take`, unwrapped (continuous across +-pi).
std::vector<double> UnwrappedHeadings(const Take& take) {
  std::vector<double> headings(take.frame_count());
  for (size_t frame_idx = 0; frame_idx < take.frame_count(); ++frame_idx) {
    const double heading = HeadingOf(take.rotation(frame_idx, 0).normalized());
    headings[frame_idx] =
        frame_idx == 0 ? heading
                       : headings[frame_idx - 1] + WrapAngle(heading - headings[frame_idx - 1]);
  }
  return headings;
}

// Capture glitches of `take` (a joint turning by more than kGlitchDegrees between two frames,
// e.g. the 180-degree flips of some converted BVH takes) as source frame ranges [f - 1, f].
std::vector<std::pair<double, double>> GlitchRanges(const Take& take) {
  std::vector<std::pair<double, double>> ranges;
  const double glitch_cos = std::cos(DegreesToRadians(kGlitchDegrees) / 2);
  for (size_t frame_idx = 1; frame_idx < take.frame_count(); ++frame_idx) {
    for (size_t joint_idx = 0; joint_idx < take.joint_count(); ++joint_idx) {
      const double dot = std::abs(take.rotation(frame_idx, joint_idx)
                                      .normalized()
                                      .dot(take.rotation(frame_idx - 1, joint_idx).normalized()));
      if (dot < glitch_cos) {
        const double frame = static_cast<double>(frame_idx);
        ranges.emplace_back(frame - 1, frame);
        break;
      }
    }
  }
  return ranges;
}

}  // namespace

TakeResequencer::TakeResequencer(const SynthOptions& options, std::vector<Take> sources,
                                 const SynthPlan& plan)
    : options_(options), plan_(plan), sources_(std::move(sources)) {
  uint64_t total = 0;
  for (const Take& take : sources_) {
    headings_.push_back(UnwrappedHeadings(take));
    total += take.frame_count();
    cumulative_frames_.push_back(total);
  }
  // Capture glitches are kept out of every piece drawn.
  reserved_.resize(sources_.size());
  for (size_t take_idx = 0; take_idx < sources_.size(); ++take_idx) {
    reserved_[take_idx] = GlitchRanges(sources_[take_idx]);
  }
  // Each motif is a piece of a source, with room around it for the blend ramps when possible,
  // clear of glitches and of the other motifs' pieces.
  const double margin = 2.5 * static_cast<double>(plan.crossfade_frames()) + 2;
  for (size_t motif_idx = 0; motif_idx < plan.motif_frames().size(); ++motif_idx) {
    const MotifSource source = DrawMotifSource(motif_idx, margin);
    const double motif_frames = static_cast<double>(plan.motif_frames()[motif_idx]);
    motif_sources_.push_back(source);
    reserved_[source.take_idx].emplace_back(source.start - margin,
                                            source.start + motif_frames + margin);
    std::sort(reserved_[source.take_idx].begin(), reserved_[source.take_idx].end());
  }
  for (auto& ranges : reserved_) std::sort(ranges.begin(), ranges.end());
}

TakeResequencer::MotifSource TakeResequencer::DrawMotifSource(size_t motif_idx,
                                                              double margin) const {
  SynthRandom random(DeriveSeed(options_.seed, SeedStream::kResequenceMotif, motif_idx));
  const double motif_frames = static_cast<double>(plan_.motif_frames()[motif_idx]);
  // Takes with room for the motif and its margins, drawn in proportion to that room.
  std::vector<double> room(sources_.size());
  double total_room = 0;
  for (size_t take_idx = 0; take_idx < sources_.size(); ++take_idx) {
    const double frames = static_cast<double>(sources_[take_idx].frame_count());
    room[take_idx] = std::max(0.0, frames - motif_frames - 2 * margin);
    total_room += room[take_idx];
  }
  MotifSource source;
  if (total_room > 0) {
    for (int attempt = 0; attempt < kDrawAttempts; ++attempt) {
      double target = random.Uniform(0, total_room);
      source.take_idx = 0;
      while (source.take_idx + 1 < sources_.size() && target >= room[source.take_idx]) {
        target -= room[source.take_idx++];
      }
      while (room[source.take_idx] == 0) --source.take_idx;  // rounding at the end
      source.start = std::floor(margin + random.Uniform(0, room[source.take_idx]));
      if (!OverlapsReserved(source.take_idx, source.start - margin,
                            source.start + motif_frames + margin)) {
        break;
      }
    }
    return source;
  }
  // No take has room for the margins: the longest take, the ramps hold at its ends.
  for (size_t take_idx = 0; take_idx < sources_.size(); ++take_idx) {
    if (sources_[take_idx].frame_count() > sources_[source.take_idx].frame_count()) {
      source.take_idx = take_idx;
    }
  }
  const double frames = static_cast<double>(sources_[source.take_idx].frame_count());
  source.start = std::floor(random.Uniform(0, std::max(0.0, frames - motif_frames) + 1));
  return source;
}

bool TakeResequencer::OverlapsReserved(size_t take_idx, double first, double last) const {
  for (const auto& range : reserved_[take_idx]) {
    if (range.first > last) break;
    if (range.second >= first) return true;
  }
  return false;
}

void TakeResequencer::SampleRoot(size_t take_idx, double source_frame, double* heading,
                                 Eigen::Vector3d* position) const {
  const Take& take = sources_[take_idx];
  const double last = static_cast<double>(take.frame_count() - 1);
  const double clamped = std::clamp(source_frame, 0.0, last);
  const size_t below = static_cast<size_t>(clamped);
  const size_t above = std::min(below + 1, take.frame_count() - 1);
  const double fraction = clamped - static_cast<double>(below);
  const std::vector<double>& headings = headings_[take_idx];
  *heading = headings[below] + fraction * (headings[above] - headings[below]);
  *position = take.root_positions[below] +
              fraction * (take.root_positions[above] - take.root_positions[below]);
}

void TakeResequencer::SampleMotion(size_t take_idx, double source_frame, double previous_frame,
                                   FrameMotion* motion) const {
  const Take& take = sources_[take_idx];
  const size_t joint_count = take.joint_count();
  const double last = static_cast<double>(take.frame_count() - 1);
  const double clamped = std::clamp(source_frame, 0.0, last);
  const size_t below = static_cast<size_t>(clamped);
  const size_t above = std::min(below + 1, take.frame_count() - 1);
  const double fraction = clamped - static_cast<double>(below);
  motion->rotations.resize(joint_count);
  for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    const Eigen::Quaterniond& a = take.rotation(below, joint_idx);
    motion->rotations[joint_idx] =
        fraction == 0 ? a : a.slerp(fraction, take.rotation(above, joint_idx));
  }
  double heading = 0;
  Eigen::Vector3d position;
  SampleRoot(take_idx, source_frame, &heading, &position);
  // The sampled root's own heading, kept on the branch of the interpolated unwrapped heading.
  const Eigen::Quaterniond root = motion->rotations[0].normalized();
  const double root_heading = heading + WrapAngle(HeadingOf(root) - heading);
  motion->rotations[0] = RemoveHeading(root, root_heading);
  double previous_heading = 0;
  Eigen::Vector3d previous_position;
  SampleRoot(take_idx, previous_frame, &previous_heading, &previous_position);
  motion->heading_delta = heading - previous_heading;
  motion->local_delta = AxisRotation(Axis::kY, -heading) * (position - previous_position);
  motion->height = position.y();
}

double TakeResequencer::ClearUntil(size_t take_idx, double first) const {
  for (const auto& range : reserved_[take_idx]) {
    if (range.second < first) continue;
    if (range.first <= first) return -1;  // `first` is inside a reserved range
    return range.first;
  }
  return static_cast<double>(sources_[take_idx].frame_count() - 1);
}

TakeResequencer::SourceSegment TakeResequencer::DrawSegment(int64_t start, int64_t overlap,
                                                            SynthRandom* random) const {
  const double fps = options_.fps;
  SourceSegment segment;
  segment.start = start;
  segment.crossfade = std::max<int64_t>(1, std::llround(random->Uniform(0.25, 0.5) * fps));
  // Longer than the previous segment's crossfade and its own: at most two segments overlap.
  const int64_t shortest = overlap + segment.crossfade + 1;
  const int64_t wanted = std::max<int64_t>(
      shortest,
      std::llround(random->Uniform(options_.segment_seconds_min, options_.segment_seconds_max) *
                   fps));
  const int64_t acceptable =
      std::max<int64_t>(shortest, std::llround(options_.segment_seconds_min * fps));
  segment.rate = 1.0 / random->Uniform(options_.source_warp_min, options_.source_warp_max);
  // A random start in a random take (drawn by length); the piece ends early rather than run
  // into a motif's piece or a glitch. The longest clear piece of a few draws is kept.
  int64_t best_frames = -1;
  for (int attempt = 0; attempt < kDrawAttempts && best_frames < acceptable; ++attempt) {
    const uint64_t target = random->UniformInt(0, cumulative_frames_.back() - 1);
    const size_t take_idx =
        std::upper_bound(cumulative_frames_.begin(), cumulative_frames_.end(), target) -
        cumulative_frames_.begin();
    const double first =
        random->Uniform(0, static_cast<double>(sources_[take_idx].frame_count() - 1));
    const double clear_until = ClearUntil(take_idx, first);
    if (clear_until < first) continue;
    const int64_t frames =
        std::min<int64_t>(wanted, static_cast<int64_t>((clear_until - first) / segment.rate) + 1);
    if (frames > best_frames) {
      best_frames = frames;
      segment.take_idx = take_idx;
      segment.source_start = first;
    }
  }
  if (best_frames >= shortest) {
    segment.frames = best_frames;
  } else {
    // Nothing clear and long enough was drawn: the start of the longest take (if even that is
    // too short, sampling holds its last frame).
    size_t longest = 0;
    for (size_t take_idx = 1; take_idx < sources_.size(); ++take_idx) {
      if (sources_[take_idx].frame_count() > sources_[longest].frame_count()) longest = take_idx;
    }
    segment.take_idx = longest;
    segment.source_start = 0;
    segment.frames = std::max<int64_t>(
        shortest,
        std::min<int64_t>(
            wanted, static_cast<int64_t>(static_cast<double>(sources_[longest].frame_count() - 1) /
                                         segment.rate) +
                        1));
  }
  segment.noise = RotationNoise(random->Next(), sources_[0].joint_count(), options_.noise_degrees);
  return segment;
}

// The background of a clip: random source segments one after the other, each crossfading into
// the next; each segment's track keeps its rotations' signs continuous in time.
class TakeResequencer::SegmentTrack {
 public:
  // Draws the first two segments from `random` (which must outlive this object).
  SegmentTrack(const TakeResequencer& owner, SynthRandom* random)
      : owner_(owner),
        random_(random),
        current_(owner.DrawSegment(0, 0, random)),
        next_(owner.DrawSegment(current_.frames - current_.crossfade, current_.crossfade, random)) {
  }

  const SourceSegment& current() const { return current_; }

  // The background motion at clip frame `frame`; frames come in order, from 0.
  void MotionAt(int64_t frame, FrameMotion* motion) {
    while (frame >= current_.start + current_.frames) {
      current_ = std::move(next_);
      next_ = owner_.DrawSegment(current_.start + current_.frames - current_.crossfade,
                                 current_.crossfade, random_);
      last_current_.swap(last_next_);
    }
    Evaluate(current_, frame, motion);
    AlignSigns(last_current_, &motion->rotations);
    last_current_ = motion->rotations;
    if (frame >= next_.start) {
      Evaluate(next_, frame, &other_);
      // The next track starts on the current one's side.
      AlignSigns(frame == next_.start ? motion->rotations : last_next_, &other_.rotations);
      last_next_ = other_.rotations;
      motion->BlendToward(other_, SmootherStep(static_cast<double>(frame - next_.start + 1) /
                                               static_cast<double>(current_.crossfade + 1)));
    }
  }

 private:
  void Evaluate(const SourceSegment& segment, int64_t frame, FrameMotion* out) const {
    const double offset = static_cast<double>(frame - segment.start);
    const double source_frame = segment.source_start + offset * segment.rate;
    owner_.SampleMotion(segment.take_idx, source_frame, source_frame - segment.rate, out);
    segment.noise.Apply(offset / owner_.options_.fps, &out->rotations);
  }

  const TakeResequencer& owner_;
  SynthRandom* random_;
  SourceSegment current_;
  SourceSegment next_;
  FrameMotion other_;
  // Each track's rotations at its previous frame, for sign continuity.
  std::vector<Eigen::Quaterniond> last_current_;
  std::vector<Eigen::Quaterniond> last_next_;
};

// The planted instances of a clip, in order: each (its motif's source piece, time-warped, with
// its own noise) blended over the background, with its ramps.
class TakeResequencer::InstanceTrack {
 public:
  InstanceTrack(const TakeResequencer& owner, uint64_t clip_idx)
      : owner_(owner),
        crossfade_(static_cast<int64_t>(owner.plan_.crossfade_frames())),
        joint_count_(owner.sources_[0].joint_count()) {
    owner.plan_.ClipInstances(clip_idx, &first_instance_, &instance_count_);
  }

  // Blends the instance whose range (with its ramps) holds clip frame `frame`, if any, into
  // *motion; frames come in order.
  void BlendInto(int64_t frame, FrameMotion* motion) {
    const std::vector<PlannedInstance>& instances = owner_.plan_.instances();
    while (cursor_ < instance_count_ &&
           frame >=
               static_cast<int64_t>(instances[first_instance_ + cursor_].truth.end) + crossfade_) {
      ++cursor_;
    }
    if (cursor_ >= instance_count_) return;
    const PlannedInstance& instance = instances[first_instance_ + cursor_];
    const int64_t offset = frame - static_cast<int64_t>(instance.truth.start);
    if (offset < -crossfade_) return;
    if (noise_owner_ != cursor_) {
      noise_ = RotationNoise(instance.noise_seed, joint_count_, owner_.options_.noise_degrees);
      noise_owner_ = cursor_;
    }
    const MotifSource& source = owner_.motif_sources_[instance.truth.motif];
    const double motif_time = instance.MotifTime(static_cast<double>(offset));
    const double previous_time = instance.MotifTime(static_cast<double>(offset - 1));
    owner_.SampleMotion(source.take_idx, source.start + motif_time, source.start + previous_time,
                        &other_);
    noise_.Apply(static_cast<double>(offset) / owner_.options_.fps, &other_.rotations);
    // An instance's track starts on the background's side.
    AlignSigns(offset == -crossfade_ ? motion->rotations : last_instance_, &other_.rotations);
    last_instance_ = other_.rotations;
    motion->BlendToward(
        other_, InstanceBlendWeight(offset, static_cast<int64_t>(instance.frames()), crossfade_));
  }

 private:
  const TakeResequencer& owner_;
  const int64_t crossfade_;
  const size_t joint_count_;
  size_t first_instance_ = 0;
  size_t instance_count_ = 0;
  size_t cursor_ = 0;  // the clip's instance now or next
  RotationNoise noise_;
  size_t noise_owner_ = SIZE_MAX;  // the instance noise_ was drawn for
  FrameMotion other_;
  std::vector<Eigen::Quaterniond> last_instance_;
};

Take TakeResequencer::EmptyClipTake(uint64_t clip_idx, size_t skeleton_take_idx) const {
  const double fps = options_.fps;
  const size_t frame_count = plan_.clip_frames()[clip_idx];
  Take take;
  take.name = SynthPlan::ClipName(clip_idx);
  take.source_path = "synthetic";
  take.fps = fps;
  take.source_fps = fps;
  take.meters_per_unit = sources_[0].meters_per_unit;
  take.skeleton = sources_[skeleton_take_idx].skeleton;
  take.root_positions.resize(frame_count);
  take.rotations.resize(frame_count * sources_[0].joint_count());
  return take;
}

Take TakeResequencer::GenerateClip(uint64_t clip_idx) const {
  const size_t frame_count = plan_.clip_frames()[clip_idx];
  const size_t joint_count = sources_[0].joint_count();
  // The clip's draws in this order: its first two segments, its start heading and position,
  // then a segment whenever one ends.
  SynthRandom random(DeriveSeed(options_.seed, SeedStream::kClip, clip_idx));
  SegmentTrack background(*this, &random);
  Take take = EmptyClipTake(clip_idx, background.current().take_idx);
  double heading = random.Uniform(-kPi, kPi);
  Eigen::Vector3d position(random.Uniform(-100, 100), 0, random.Uniform(-100, 100));
  InstanceTrack instances(*this, clip_idx);
  FrameMotion motion;
  for (size_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    const int64_t frame = static_cast<int64_t>(frame_idx);
    background.MotionAt(frame, &motion);
    instances.BlendInto(frame, &motion);
    // The root integrates the blended increments from the clip's start heading and position.
    if (frame_idx > 0) {
      heading += motion.heading_delta;
      position += AxisRotation(Axis::kY, heading) * motion.local_delta;
    }
    position.y() = motion.height;
    take.root_positions[frame_idx] = position;
    Eigen::Quaterniond* rotations = &take.rotations[frame_idx * joint_count];
    rotations[0] = AxisRotation(Axis::kY, heading) * motion.rotations[0].normalized();
    for (size_t joint_idx = 1; joint_idx < joint_count; ++joint_idx) {
      rotations[joint_idx] = motion.rotations[joint_idx].normalized();
    }
  }
  return take;
}

}  // namespace motif
