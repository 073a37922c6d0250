#include "bench/bench_archives.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>
#include <vector>

#include "bench/bench_util.h"
#include "engine/synth/motion_synthesizer.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/import/take_importer.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/resample.h"

namespace motif::bench {
namespace {

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

// The real takes, imported (not cached: an archive is written once per size and kept, and
// whatever a cache held would count in the memory of the benchmarks that run after).
Result<std::vector<Take>> RealTakes() {
  const std::string mocap = MocapDir();
  if (mocap.empty()) return Status::NotFound("real CMU takes not found: set MOTIF_MOCAP_DIR");
  MOTIF_ASSIGN_OR_RETURN(std::vector<TakeSource> sources,
                         DiscoverTakes({mocap + "/bvh"}, ImportOptions()));
  std::vector<Take> takes;
  for (const TakeSource& source : sources) {
    MOTIF_ASSIGN_OR_RETURN(Take take, ImportTake(source, ImportOptions()));
    if (!takes.empty() && !ConformToSkeleton(takes[0].skeleton, &take).ok()) continue;
    takes.push_back(ResampleTake(take, 120.0));
  }
  return takes;
}

SynthOptions OptionsFor(uint64_t frames) {
  SynthOptions options;
  options.frames = frames;
  options.seed = 7;
  options.motifs = static_cast<uint32_t>(std::clamp<uint64_t>(frames / 10000, 1, 8));
  options.motif_seconds_max = frames < 20000 ? 2.0 : 5.0;
  return options;
}

Result<std::unique_ptr<MotionSynthesizer>> SynthesizerFor(const std::string& data,
                                                          const SynthOptions& options) {
  if (data == "resequenced") {
    MOTIF_ASSIGN_OR_RETURN(std::vector<Take> takes, RealTakes());
    return MotionSynthesizer::CreateFromTakes(options, std::move(takes));
  }
  if (data == "synth") return MotionSynthesizer::Create(options);
  return Status::InvalidArgument("no archive kind '" + data + "' (synth, resequenced)");
}

// The "heavy" archive: synthetic motion, then a T-pose (identity rotations) held still for
// static_frames frames, as one more clip.
Result<PoseFeatures> HeavyFeatures(uint64_t frames, uint64_t static_frames) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<MotionSynthesizer> synthesizer,
                         SynthesizerFor("synth", OptionsFor(frames - static_frames)));
  const Skeleton& skeleton = synthesizer->skeleton();
  const FrameLayout layout{static_cast<uint32_t>(skeleton.joint_count())};
  std::vector<float> rows;
  std::vector<uint64_t> clip_first_frames;
  uint64_t total = 0;
  MOTIF_RETURN_IF_ERROR(synthesizer->Run([&](const ClipFrames& clip) {
    clip_first_frames.push_back(total);
    rows.insert(rows.end(), clip.rows.begin(), clip.rows.end());
    total += clip.rows.size() / layout.stride();
    return Status::Ok();
  }));
  clip_first_frames.push_back(total);
  const size_t first = rows.size();
  rows.resize(first + static_frames * layout.stride(), 0.0f);
  for (uint64_t frame_idx = 0; frame_idx < static_frames; ++frame_idx) {
    for (uint32_t joint_idx = 0; joint_idx < layout.joint_count; ++joint_idx) {
      rows[first + frame_idx * layout.stride() + 4 * joint_idx] = 1.0f;
    }
  }
  total += static_frames;
  std::vector<float> weights;
  for (size_t joint_idx = 0; joint_idx < skeleton.joint_count(); ++joint_idx) {
    weights.push_back(skeleton.joint(joint_idx).weight);
  }
  return PoseFeatures::FromRows(rows.data(), total, layout.joint_count, weights, clip_first_frames);
}

Result<PoseFeatures> FeaturesOfFile(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileReader> reader, FrameFileReader::Open(path));
  MOTIF_ASSIGN_OR_RETURN(std::vector<float> weights, LoadDistanceWeights(reader->skeleton(), ""));
  return PoseFeatures::FromArchive(*reader, weights);
}

std::string cached_key;
Archive cached;

}  // namespace

Result<std::string> ArchiveFileOf(const std::string& data, uint64_t frames) {
  const std::string dir = WorkDir() + "/archives";
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  const std::string path = dir + "/" + data + "-" + std::to_string(frames) + ".mfs";
  if (std::filesystem::exists(path, error)) {
    Result<std::unique_ptr<FrameFileReader>> existing = FrameFileReader::Open(path);
    if (existing.ok() && (*existing)->frame_count() == frames) return path;
    std::filesystem::remove(path, error);
  }
  const SynthOptions options = OptionsFor(frames);
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<MotionSynthesizer> synthesizer,
                         SynthesizerFor(data, options));
  const std::string staging = path + ".tmp-" + std::to_string(::getpid());
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileWriter> writer,
                         FrameFileWriter::Create(staging, synthesizer->skeleton(), options.fps));
  MOTIF_RETURN_IF_ERROR(
      synthesizer->Run([&](const ClipFrames& clip) { return writer->AppendClip(clip); }));
  MOTIF_RETURN_IF_ERROR(writer->Commit());
  std::filesystem::rename(staging, path, error);
  if (error) return Status::IOError(path + ": " + error.message());
  return path;
}

const Archive& ArchiveOf(const std::string& data, uint64_t frames) {
  const std::string key = data + "/" + std::to_string(frames);
  if (key == cached_key) return cached;
  ReleaseArchive();
  cached_key = key;
  const uint64_t static_frames = data == "heavy" ? frames / 16 : 0;
  Result<PoseFeatures> features = Status::NotFound("unset");
  if (data == "heavy") {
    features = HeavyFeatures(frames, static_frames);
  } else {
    Result<std::string> path = ArchiveFileOf(data, frames);
    features = path.ok() ? FeaturesOfFile(*path) : Result<PoseFeatures>(path.status());
  }
  if (!features.ok()) {
    cached.error = features.status().ToString();
    return cached;
  }
  cached.features = std::make_unique<PoseFeatures>(std::move(features).value());
  // eps from the moving frames only (the T-pose clip is the last; it would pull mu and sigma).
  cached.rules = RulesFor(*cached.features, cached.features->frame_count() - static_frames);
  return cached;
}

void ReleaseArchive() {
  cached = Archive();
  cached_key.clear();
}

}  // namespace motif::bench
