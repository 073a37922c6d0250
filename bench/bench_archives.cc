#include "bench/bench_archives.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "bench/bench_util.h"
#include "engine/synth/motion_synthesizer.h"
#include "formats/import/take_importer.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/resample.h"

namespace motif::bench {
namespace {

PoseFeatures FeaturesFromClips(const Skeleton& skeleton, const std::vector<ClipFrames>& clips,
                               uint64_t static_frames) {
  const FrameLayout layout{static_cast<uint32_t>(skeleton.joint_count())};
  std::vector<float> rows;
  std::vector<uint64_t> clip_first_frames;
  uint64_t frames = 0;
  for (const ClipFrames& clip : clips) {
    clip_first_frames.push_back(frames);
    rows.insert(rows.end(), clip.rows.begin(), clip.rows.end());
    frames += clip.rows.size() / layout.stride();
  }
  if (static_frames > 0) {  // one more clip: a T-pose (identity rotations) held still
    clip_first_frames.push_back(frames);
    const size_t first = rows.size();
    rows.resize(first + static_frames * layout.stride(), 0.0f);
    for (uint64_t frame_idx = 0; frame_idx < static_frames; ++frame_idx) {
      for (uint32_t joint_idx = 0; joint_idx < layout.joint_count; ++joint_idx) {
        rows[first + frame_idx * layout.stride() + 4 * joint_idx] = 1.0f;
      }
    }
    frames += static_frames;
  }
  std::vector<float> weights;
  for (size_t joint_idx = 0; joint_idx < skeleton.joint_count(); ++joint_idx) {
    weights.push_back(skeleton.joint(joint_idx).weight);
  }
  return PoseFeatures::FromRows(rows.data(), frames, layout.joint_count, weights,
                                clip_first_frames);
}

// eps = mu - 2 sigma of 20,000 random allowed pairs among frames [0, sample_frames).
NeighbourRules RulesFor(const PoseFeatures& features, uint64_t sample_frames) {
  NeighbourRules rules;
  rules.k_max = 256;
  rules.exclusion_frames = 30;
  rules.clip_first_frames = features.clip_first_frames();
  uint64_t state = 3;
  double sum = 0;
  double squares = 0;
  uint32_t taken = 0;
  while (taken < 20000) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const uint64_t a = (state >> 17) % sample_frames;
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const uint64_t b = (state >> 17) % sample_frames;
    if (rules.Excluded(a, b, features.ClipOf(a), features.ClipOf(b))) continue;
    const double distance = PoseDistance(features, a, b);
    sum += distance;
    squares += distance * distance;
    ++taken;
  }
  const double mean = sum / taken;
  rules.eps =
      static_cast<float>(mean - 2 * std::sqrt(std::max(0.0, squares / taken - mean * mean)));
  return rules;
}

// The real takes, imported once per process (a copy is handed out: the synthesiser takes them).
std::vector<Take> RealTakes(std::string* error) {
  static std::vector<Take> takes;
  static std::string load_error;
  static bool loaded = false;
  if (!loaded) {
    loaded = true;
    const std::string mocap = MocapDir();
    if (mocap.empty()) {
      load_error = "real CMU takes not found: set MOTIF_MOCAP_DIR";
    } else {
      auto sources = DiscoverTakes({mocap + "/bvh"}, ImportOptions());
      if (!sources.ok()) load_error = sources.status().ToString();
      for (size_t idx = 0; sources.ok() && idx < sources->size(); ++idx) {
        Result<Take> take = ImportTake((*sources)[idx], ImportOptions());
        if (!take.ok()) {
          load_error = take.status().ToString();
          break;
        }
        if (!takes.empty()) {
          Status conformed = ConformToSkeleton(takes[0].skeleton, &*take);
          if (!conformed.ok()) continue;
        }
        takes.push_back(ResampleTake(*take, 120.0));
      }
    }
  }
  *error = load_error;
  return takes;
}

}  // namespace

const Archive& ArchiveOf(const std::string& data, uint64_t frames) {
  static std::string cached_key;
  static Archive cached;
  const std::string key = data + "/" + std::to_string(frames);
  if (key == cached_key) return cached;
  cached = Archive();
  cached_key = key;
  SynthOptions options;
  options.frames = frames;
  options.seed = 7;
  options.motifs = static_cast<uint32_t>(std::clamp<uint64_t>(frames / 10000, 1, 8));
  options.motif_seconds_max = frames < 20000 ? 2.0 : 5.0;
  Result<std::unique_ptr<MotionSynthesizer>> synthesizer = Status::NotFound("unset");
  uint64_t static_frames = 0;
  if (data == "resequenced") {
    std::vector<Take> takes = RealTakes(&cached.error);
    if (!cached.error.empty()) return cached;
    synthesizer = MotionSynthesizer::CreateFromTakes(options, std::move(takes));
  } else {
    if (data == "heavy") static_frames = frames / 16;
    options.frames = frames - static_frames;
    synthesizer = MotionSynthesizer::Create(options);
  }
  if (!synthesizer.ok()) {
    cached.error = synthesizer.status().ToString();
    return cached;
  }
  std::vector<ClipFrames> clips;
  Status status = (*synthesizer)->Run([&](const ClipFrames& clip) {
    clips.push_back(clip);
    return Status::Ok();
  });
  if (!status.ok()) {
    cached.error = status.ToString();
    return cached;
  }
  cached.features = std::make_unique<PoseFeatures>(
      FeaturesFromClips((*synthesizer)->skeleton(), clips, static_frames));
  clips = {};
  // eps from the moving frames only (the T-pose clip is the last; it would pull mu and sigma).
  cached.rules = RulesFor(*cached.features, cached.features->frame_count() - static_frames);
  return cached;
}

}  // namespace motif::bench
