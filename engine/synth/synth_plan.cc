#include "engine/synth/synth_plan.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "engine/synth/synth_random.h"
#include "formats/motion/quaternion_math.h"

namespace motif {
namespace {

// Share of the archive that planted instances (with their blends and gaps) may take: beyond it
// the archive would be mostly motifs and placement would get cramped.
constexpr double kMaxPlantedShare = 0.5;

Status Invalid(const std::string& message) {
  return Status::InvalidArgument("synth options: " + message);
}

std::string Number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%g", value);
  return buffer;
}

Status CheckRange(const char* min_name, double min_value, const char* max_name, double max_value) {
  if (!std::isfinite(min_value) || !std::isfinite(max_value)) {
    return Invalid(std::string(min_name) + " and " + max_name + " must be finite");
  }
  if (min_value > max_value) {
    return Invalid(std::string(min_name) + " (" + Number(min_value) + ") is greater than " +
                   max_name + " (" + Number(max_value) + ")");
  }
  return Status::Ok();
}

uint64_t RoundFrames(double seconds, double fps) {
  return static_cast<uint64_t>(std::llround(seconds * fps));
}

// A segment tree over the clips' remaining capacities: sampling a clip in proportion to its
// capacity, and finding the roomiest clip, both in O(log clips).
class CapacityTree {
 public:
  explicit CapacityTree(const std::vector<uint64_t>& capacities) : size_(capacities.size()) {
    while (leaf_count_ < capacities.size()) leaf_count_ <<= 1;
    sum_.assign(2 * leaf_count_, 0);
    max_.assign(2 * leaf_count_, 0);
    for (size_t idx = 0; idx < capacities.size(); ++idx) {
      sum_[leaf_count_ + idx] = max_[leaf_count_ + idx] = capacities[idx];
    }
    for (size_t node = leaf_count_ - 1; node >= 1; --node) Pull(node);
  }
  size_t size() const { return size_; }
  uint64_t total() const { return sum_[1]; }
  uint64_t largest() const { return max_[1]; }
  uint64_t capacity(size_t idx) const { return sum_[leaf_count_ + idx]; }
  // The clip in which the cumulative capacity passes `target` (< total()).
  size_t FindByPrefix(uint64_t target) const {
    size_t node = 1;
    while (node < leaf_count_) {
      if (target < sum_[2 * node]) {
        node = 2 * node;
      } else {
        target -= sum_[2 * node];
        node = 2 * node + 1;
      }
    }
    return node - leaf_count_;
  }
  size_t Largest() const {
    size_t node = 1;
    while (node < leaf_count_)
      node = max_[2 * node] >= max_[2 * node + 1] ? 2 * node : 2 * node + 1;
    return node - leaf_count_;
  }
  void Set(size_t idx, uint64_t value) {
    size_t node = leaf_count_ + idx;
    sum_[node] = max_[node] = value;
    for (node /= 2; node >= 1; node /= 2) Pull(node);
  }

 private:
  void Pull(size_t node) {
    sum_[node] = sum_[2 * node] + sum_[2 * node + 1];
    max_[node] = std::max(max_[2 * node], max_[2 * node + 1]);
  }
  size_t size_ = 0;  // clips
  size_t leaf_count_ = 1;
  std::vector<uint64_t> sum_;
  std::vector<uint64_t> max_;
};

// Clip lengths drawn uniformly from the clip length range; the last clip takes the remainder.
std::vector<uint64_t> DrawClipLayout(const SynthOptions& options) {
  const double fps = options.fps;
  SynthRandom random(DeriveSeed(options.seed, SeedStream::kClipLayout, 0));
  const uint64_t shortest = std::max<uint64_t>(1, RoundFrames(options.clip_seconds_min, fps));
  const uint64_t longest = std::max(shortest, RoundFrames(options.clip_seconds_max, fps));
  std::vector<uint64_t> clip_frames;
  uint64_t remaining = options.frames;
  while (remaining > 0) {
    const uint64_t frames = std::min(remaining, random.UniformInt(shortest, longest));
    clip_frames.push_back(frames);
    remaining -= frames;
  }
  return clip_frames;
}

// A smooth monotone map g(x) = x + c1 sin(pi x)/pi + c2 sin(2 pi x)/(2 pi): g(0) = 0,
// g(1) = 1, g' = 1 + c1 cos(pi x) + c2 cos(2 pi x) >= 0.5: the mean rate is the warp.
void DrawNonUniformWarp(SynthRandom* random, double* c1_out, double* c2_out) {
  double c1 = random->Uniform(-0.45, 0.45);
  double c2 = random->Uniform(-0.3, 0.3);
  const double total = std::abs(c1) + std::abs(c2);
  if (total > 0.5) {
    c1 *= 0.5 / total;
    c2 *= 0.5 / total;
  }
  if (std::max(std::abs(c1), std::abs(c2)) < 0.2) c1 = c1 < 0 ? -0.3 : 0.3;
  *c1_out = c1;
  *c2_out = c2;
}

// Instance `instance_idx` of motif `motif_idx`, from its own seed: its warped length (in
// truth.end until it is placed), its time map and its noise seed.
PlannedInstance DrawPlannedInstance(const SynthOptions& options, uint32_t motif_idx,
                                    uint32_t instance_idx, uint64_t motif_frames) {
  SynthRandom instance_random(
      DeriveSeed(DeriveSeed(options.seed, SeedStream::kInstances, motif_idx),
                 SeedStream::kInstances, instance_idx));
  const double span = static_cast<double>(motif_frames);
  const double lowest = std::ceil(span * options.warp_min - 1e-9);
  const double highest = std::floor(span * options.warp_max + 1e-9);
  PlannedInstance instance;
  instance.motif_frames = motif_frames;
  instance.truth.motif = motif_idx;
  double frames = std::round(span * instance_random.Uniform(options.warp_min, options.warp_max));
  if (lowest <= highest) frames = std::clamp(frames, lowest, highest);
  frames = std::max(2.0, frames);
  instance.truth.warp = frames / span;
  instance.truth.end = static_cast<uint64_t>(frames);  // a length until placed
  instance.truth.nonuniform = instance_random.Bernoulli(0.5);
  double c1 = 0;
  double c2 = 0;
  DrawNonUniformWarp(&instance_random, &c1, &c2);
  if (instance.truth.nonuniform) {
    instance.warp_c1 = c1;
    instance.warp_c2 = c2;
  }
  instance.noise_seed = instance_random.Next();
  return instance;
}

// Every motif's length and instance count, from its own seed, and its instances.
std::vector<PlannedInstance> DrawMotifInstances(const SynthOptions& options,
                                                std::vector<uint64_t>* motif_frames_out) {
  std::vector<PlannedInstance> instances;
  for (uint32_t motif_idx = 0; motif_idx < options.motifs; ++motif_idx) {
    SynthRandom random(DeriveSeed(options.seed, SeedStream::kMotifs, motif_idx));
    const uint64_t motif_frames = std::max<uint64_t>(
        2, RoundFrames(random.Uniform(options.motif_seconds_min, options.motif_seconds_max),
                       options.fps));
    motif_frames_out->push_back(motif_frames);
    const uint32_t count =
        static_cast<uint32_t>(random.UniformInt(options.instances_min, options.instances_max));
    for (uint32_t instance_idx = 0; instance_idx < count; ++instance_idx) {
      instances.push_back(DrawPlannedInstance(options, motif_idx, instance_idx, motif_frames));
    }
  }
  return instances;
}

// InvalidArgument when the planted instances, with their blends and gaps, would take more than
// kMaxPlantedShare of the frames.
Status CheckPlantedShare(const SynthOptions& options, const std::vector<PlannedInstance>& instances,
                         uint64_t crossfade, uint64_t gap) {
  uint64_t planted_frames = 0;  // with blends and gaps
  for (const PlannedInstance& instance : instances) {
    planted_frames += instance.truth.end + 2 * crossfade + gap;
  }
  if (static_cast<double>(planted_frames) >
      kMaxPlantedShare * static_cast<double>(options.frames)) {
    return Invalid("motifs: " + std::to_string(options.motifs) + " motifs with " +
                   std::to_string(options.instances_min) + ".." +
                   std::to_string(options.instances_max) + " instances of " +
                   Number(options.motif_seconds_min) + ".." + Number(options.motif_seconds_max) +
                   " s need " + std::to_string(planted_frames) +
                   " frames of planted motion (with blends and gaps), more than half of the " +
                   std::to_string(options.frames) +
                   " frames; plant fewer or shorter motifs, or generate more frames");
  }
  return Status::Ok();
}

// Each instance (longest first) goes to a clip drawn in proportion to its remaining room (16
// draws, then the roomiest clip); `tree` is left with each clip's slack.
Status AssignInstancesToClips(uint64_t crossfade, uint64_t gap, SynthRandom* random,
                              CapacityTree* tree, std::vector<PlannedInstance>* instances) {
  const size_t clip_count = tree->size();
  std::vector<size_t> order(instances->size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return (*instances)[a].truth.end > (*instances)[b].truth.end;
  });
  for (size_t instance_idx : order) {
    PlannedInstance& instance = (*instances)[instance_idx];
    const uint64_t footprint = instance.truth.end + 2 * crossfade + gap;
    size_t clip_idx = clip_count;
    for (int attempt = 0; attempt < 16 && clip_idx == clip_count && tree->total() > 0; ++attempt) {
      const size_t candidate = tree->FindByPrefix(random->UniformInt(0, tree->total() - 1));
      if (tree->capacity(candidate) >= footprint) clip_idx = candidate;
    }
    if (clip_idx == clip_count) {
      if (tree->largest() < footprint) {
        return Invalid("motifs: an instance of motif " + std::to_string(instance.truth.motif) +
                       " (" + std::to_string(instance.truth.end) +
                       " frames with its blends) does not fit in any clip with room left; "
                       "plant fewer or shorter motifs, or use longer clips (clip_seconds_min/max)");
      }
      clip_idx = tree->Largest();
    }
    instance.clip_idx = clip_idx;
    tree->Set(clip_idx, tree->capacity(clip_idx) - footprint);
  }
  return Status::Ok();
}

// The instances grouped by clip (a counting sort, stable); (*first)[clip] is where a clip's
// instances begin (clip_count + 1 entries, zero on entry).
std::vector<PlannedInstance> GroupInstancesByClip(const std::vector<PlannedInstance>& instances,
                                                  std::vector<uint64_t>* first) {
  const size_t clip_count = first->size() - 1;
  for (const PlannedInstance& instance : instances) ++(*first)[instance.clip_idx + 1];
  for (uint64_t clip_idx = 0; clip_idx < clip_count; ++clip_idx)
    (*first)[clip_idx + 1] += (*first)[clip_idx];
  std::vector<PlannedInstance> grouped(instances.size());
  std::vector<uint64_t> cursor(first->begin(), first->end() - 1);
  for (const PlannedInstance& instance : instances) grouped[cursor[instance.clip_idx]++] = instance;
  return grouped;
}

// One clip's instances, shuffled, then spread over the clip with the slack cut at random points
// between them; sorted by start.
void SpreadClipInstances(uint64_t clip_idx, uint64_t slack, uint64_t crossfade, uint64_t gap,
                         SynthRandom* random, PlannedInstance* clip_instances, size_t count) {
  for (size_t idx = count - 1; idx > 0; --idx) {  // Fisher-Yates
    std::swap(clip_instances[idx], clip_instances[random->UniformInt(0, idx)]);
  }
  std::vector<uint64_t> cuts(count);
  for (uint64_t& cut : cuts) cut = random->UniformInt(0, slack);
  std::sort(cuts.begin(), cuts.end());
  uint64_t cursor = 0;
  uint64_t previous_cut = 0;
  for (size_t idx = 0; idx < count; ++idx) {
    PlannedInstance& instance = clip_instances[idx];
    cursor += cuts[idx] - previous_cut;
    previous_cut = cuts[idx];
    const uint64_t frames = instance.truth.end;
    instance.truth.clip = SynthPlan::ClipName(clip_idx);
    instance.truth.start = cursor + crossfade;
    instance.truth.end = instance.truth.start + frames;
    cursor += frames + 2 * crossfade + gap;
  }
  std::sort(clip_instances, clip_instances + count,
            [](const PlannedInstance& a, const PlannedInstance& b) {
              return a.truth.start < b.truth.start;
            });
}

}  // namespace

double PlannedInstance::MotifTime(double offset) const {
  const double span = static_cast<double>(motif_frames - 1);
  const double last = static_cast<double>(frames() - 1);
  const double x = last > 0 ? offset / last : 0.0;
  if (x < 0) return span * (1.0 + warp_c1 + warp_c2) * x;
  if (x > 1) return span * (1.0 + (1.0 - warp_c1 + warp_c2) * (x - 1.0));
  return span *
         (x + warp_c1 * std::sin(kPi * x) / kPi + warp_c2 * std::sin(2 * kPi * x) / (2 * kPi));
}

Status ValidateSynthOptions(const SynthOptions& options) {
  if (options.frames == 0) return Invalid("frames must be at least 1");
  if (!(options.fps > 0) || !std::isfinite(options.fps)) {
    return Invalid("fps must be positive, got " + Number(options.fps));
  }
  MOTIF_RETURN_IF_ERROR(CheckRange("clip_seconds_min", options.clip_seconds_min, "clip_seconds_max",
                                   options.clip_seconds_max));
  if (options.clip_seconds_min * options.fps < 1) {
    return Invalid("clip_seconds_min (" + Number(options.clip_seconds_min) +
                   " s) is shorter than one frame at " + Number(options.fps) + " fps");
  }
  if (options.clip_seconds_max * options.fps > 1e9) {
    return Invalid("clip_seconds_max (" + Number(options.clip_seconds_max) + " s) is too long");
  }
  MOTIF_RETURN_IF_ERROR(CheckRange("motif_seconds_min", options.motif_seconds_min,
                                   "motif_seconds_max", options.motif_seconds_max));
  if (options.motifs > 0 && options.motif_seconds_min * options.fps < 2) {
    return Invalid("motif_seconds_min (" + Number(options.motif_seconds_min) +
                   " s) is shorter than two frames at " + Number(options.fps) + " fps");
  }
  if (options.motif_seconds_max * options.fps > 1e8) {
    return Invalid("motif_seconds_max (" + Number(options.motif_seconds_max) + " s) is too long");
  }
  if (options.instances_min > options.instances_max) {
    return Invalid("instances_min (" + std::to_string(options.instances_min) +
                   ") is greater than instances_max (" + std::to_string(options.instances_max) +
                   ")");
  }
  if (options.motifs > 0 && options.instances_min < 2) {
    return Invalid("instances_min must be at least 2 (a motif is a movement that repeats), got " +
                   std::to_string(options.instances_min));
  }
  if (!(options.warp_min > 0))
    return Invalid("warp_min must be positive, got " + Number(options.warp_min));
  MOTIF_RETURN_IF_ERROR(CheckRange("warp_min", options.warp_min, "warp_max", options.warp_max));
  if (!(options.noise_degrees >= 0) || !(options.noise_degrees <= 20)) {
    return Invalid("noise_degrees must be in [0, 20], got " + Number(options.noise_degrees));
  }
  if (!(options.background_variation_degrees >= 0) ||
      !(options.background_variation_degrees <= 20)) {
    return Invalid("background_variation_degrees must be in [0, 20], got " +
                   Number(options.background_variation_degrees));
  }
  if (!(options.crossfade_seconds >= 0) || !std::isfinite(options.crossfade_seconds)) {
    return Invalid("crossfade_seconds must be non-negative, got " +
                   Number(options.crossfade_seconds));
  }
  if (!(options.gap_seconds >= 0) || !std::isfinite(options.gap_seconds)) {
    return Invalid("gap_seconds must be non-negative, got " + Number(options.gap_seconds));
  }
  if (options.activities == 0) return Invalid("activities must be at least 1");
  if (!(options.segment_seconds_min > 0)) {
    return Invalid("segment_seconds_min must be positive, got " +
                   Number(options.segment_seconds_min));
  }
  MOTIF_RETURN_IF_ERROR(CheckRange("segment_seconds_min", options.segment_seconds_min,
                                   "segment_seconds_max", options.segment_seconds_max));
  if (!(options.source_warp_min > 0)) {
    return Invalid("source_warp_min must be positive, got " + Number(options.source_warp_min));
  }
  MOTIF_RETURN_IF_ERROR(CheckRange("source_warp_min", options.source_warp_min, "source_warp_max",
                                   options.source_warp_max));
  return Status::Ok();
}

std::string SynthPlan::ClipName(uint64_t clip_idx) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "synth_%06" PRIu64, clip_idx);
  return buffer;
}

void SynthPlan::ClipInstances(uint64_t clip_idx, size_t* first, size_t* count) const {
  *first = clip_first_instance_[clip_idx];
  *count = clip_first_instance_[clip_idx + 1] - clip_first_instance_[clip_idx];
}

Result<SynthPlan> SynthPlan::Create(const SynthOptions& options) {
  MOTIF_RETURN_IF_ERROR(ValidateSynthOptions(options));
  SynthPlan plan;
  const double fps = options.fps;
  plan.crossfade_frames_ = RoundFrames(options.crossfade_seconds, fps);
  if (options.crossfade_seconds > 0)
    plan.crossfade_frames_ = std::max<uint64_t>(1, plan.crossfade_frames_);
  plan.gap_frames_ = RoundFrames(options.gap_seconds, fps);
  plan.clip_frames_ = DrawClipLayout(options);
  const uint64_t clip_count = plan.clip_frames_.size();
  plan.clip_first_instance_.assign(clip_count + 1, 0);
  if (options.motifs == 0) return plan;

  const uint64_t crossfade = plan.crossfade_frames_;
  const uint64_t gap = plan.gap_frames_;
  std::vector<PlannedInstance> instances = DrawMotifInstances(options, &plan.motif_frames_);
  MOTIF_RETURN_IF_ERROR(CheckPlantedShare(options, instances, crossfade, gap));

  // Placement: each instance goes to a clip; then each clip's instances are shuffled and spread
  // with random gaps, all from one placement stream.
  SynthRandom random(DeriveSeed(options.seed, SeedStream::kPlacement, 0));
  std::vector<uint64_t> capacities(clip_count);
  for (uint64_t clip_idx = 0; clip_idx < clip_count; ++clip_idx) {
    capacities[clip_idx] = plan.clip_frames_[clip_idx] + gap;
  }
  CapacityTree tree(capacities);
  MOTIF_RETURN_IF_ERROR(AssignInstancesToClips(crossfade, gap, &random, &tree, &instances));
  std::vector<uint64_t>& first = plan.clip_first_instance_;
  std::vector<PlannedInstance> grouped = GroupInstancesByClip(instances, &first);
  for (uint64_t clip_idx = 0; clip_idx < clip_count; ++clip_idx) {
    const size_t begin = first[clip_idx];
    const size_t count = first[clip_idx + 1] - begin;
    if (count == 0) continue;
    SpreadClipInstances(clip_idx, tree.capacity(clip_idx), crossfade, gap, &random,
                        grouped.data() + begin, count);
  }
  plan.instances_ = std::move(grouped);
  plan.truth_.reserve(plan.instances_.size());
  for (const PlannedInstance& instance : plan.instances_) plan.truth_.push_back(instance.truth);
  return plan;
}

}  // namespace motif
