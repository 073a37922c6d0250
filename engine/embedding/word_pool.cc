#include "engine/embedding/word_pool.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <numeric>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "common/split_mix64.h"
#include "engine/embedding/word_input.h"
#include "engine/signature/word_stream.h"

namespace motif {

struct WordPool::ClipData {
  uint64_t words = 0;
  std::vector<int16_t> features;   // words x versions x W x 4 J_w
  std::vector<float> root_motion;  // words x versions x W x 4
};

namespace {

// The seed of copy `copy` of the word with archive id `word_id`: a mix of the three, so copies of
// different words and runs with different seeds are independent.
uint64_t WarpSeed(uint64_t seed, uint64_t word_id, uint32_t copy) {
  SplitMix64 mix(seed ^ (word_id * 0x9e3779b97f4a7c15ull) ^ (uint64_t{copy} << 56));
  return mix.Next();
}

}  // namespace

Status ValidateWordPoolOptions(const WordPoolOptions& options) {
  MOTIF_RETURN_IF_ERROR(ValidateWordOptions(options.words));
  MOTIF_RETURN_IF_ERROR(ValidateTimeWarpOptions(options.warp));
  if (options.max_words == 0) return Status::InvalidArgument("word pool: max_words must be >= 1");
  if (options.warp_copies > 64) {
    return Status::InvalidArgument("word pool: warp_copies must be at most 64");
  }
  if (!(options.held_out_fraction >= 0 && options.held_out_fraction < 1)) {
    return Status::InvalidArgument("word pool: held_out_fraction must be in [0, 1)");
  }
  return Status::Ok();
}

WordPool::ClipData WordPool::MakeClipData(const ClipWords& clip, uint64_t word_count,
                                          const WordPoolOptions& options) {
  const FrameResampler& resampler = clip.resampler();
  const uint32_t frames = clip.grid().options().word_frames;
  const double word_fps = clip.grid().options().word_fps;
  const size_t feature_values = frames * resampler.feature_values();
  const size_t root_values = frames * kRootMotionChannels;
  const uint32_t versions = 1 + options.warp_copies;
  ClipData data;
  data.words = word_count;
  data.features.resize(word_count * versions * feature_values);
  data.root_motion.resize(word_count * versions * root_values);
  WordBatch batch;
  clip.AllWords(&batch, /*keep_rows=*/true);
  std::vector<float> rows(frames * resampler.layout().stride());
  for (uint64_t word = 0; word < word_count; ++word) {
    const size_t slot = word * versions;
    std::memcpy(&data.features[slot * feature_values], batch.word(word),
                feature_values * sizeof(int16_t));
    RootMotionFromRows(resampler.layout(), batch.rows(word), frames, word_fps, 1.0,
                       &data.root_motion[slot * root_values]);
    for (uint32_t copy = 1; copy < versions; ++copy) {
      const double speed = clip.RandomWarpedWord(
          word, WarpSeed(options.seed, batch.info(word).word_id, copy), options.warp,
          &data.features[(slot + copy) * feature_values], rows.data());
      RootMotionFromRows(resampler.layout(), rows.data(), frames, word_fps, speed,
                         &data.root_motion[(slot + copy) * root_values]);
    }
  }
  return data;
}

Result<WordPool> WordPool::Assemble(std::vector<PoolClip> clips, std::vector<ClipData> data,
                                    const FrameResampler& resampler,
                                    const WordPoolOptions& options) {
  WordPool pool;
  pool.versions_ = 1 + options.warp_copies;
  pool.word_frames_ = options.words.word_frames;
  pool.weighted_joints_ = resampler.weighted_joint_count();
  pool.weights_ = resampler.weights();
  pool.overlap_words_ =
      (options.words.word_frames + options.words.stride_frames - 1) / options.words.stride_frames;
  // Held-out clips: the first round(fraction * clips) of a seeded permutation, at least one and
  // leaving at least one for training when the fraction is positive and there are two clips.
  if (options.held_out_fraction > 0 && clips.size() >= 2) {
    std::vector<size_t> order(clips.size());
    std::iota(order.begin(), order.end(), 0);
    SplitMix64 random(options.seed ^ 0x68656c646f7574ull);  // "heldout"
    for (size_t idx = order.size() - 1; idx > 0; --idx) {
      std::swap(order[idx], order[random.Below(idx + 1)]);
    }
    const size_t held = std::clamp<size_t>(
        static_cast<size_t>(std::llround(options.held_out_fraction * clips.size())), 1,
        clips.size() - 1);
    for (size_t idx = 0; idx < held; ++idx) clips[order[idx]].held_out = true;
  }
  uint64_t total = 0;
  for (size_t clip_idx = 0; clip_idx < clips.size(); ++clip_idx) {
    clips[clip_idx].first_word = total;
    total += data[clip_idx].words;
  }
  pool.word_clip_.resize(total);
  for (size_t clip_idx = 0; clip_idx < clips.size(); ++clip_idx) {
    std::fill_n(pool.word_clip_.begin() + clips[clip_idx].first_word, data[clip_idx].words,
                static_cast<uint32_t>(clip_idx));
    pool.features_.insert(pool.features_.end(), data[clip_idx].features.begin(),
                          data[clip_idx].features.end());
    pool.root_motion_.insert(pool.root_motion_.end(), data[clip_idx].root_motion.begin(),
                             data[clip_idx].root_motion.end());
    std::vector<int16_t>().swap(data[clip_idx].features);
    std::vector<float>().swap(data[clip_idx].root_motion);
  }
  pool.clips_ = std::move(clips);
  return pool;
}

Result<WordPool> WordPool::FromClips(std::span<const ClipWords> clips,
                                     const WordPoolOptions& options) {
  MOTIF_RETURN_IF_ERROR(ValidateWordPoolOptions(options));
  if (clips.empty()) return Status::InvalidArgument("word pool: no clips");
  std::vector<PoolClip> pool_clips;
  std::vector<ClipData> data;
  uint64_t word_id = 0;
  for (size_t clip_idx = 0; clip_idx < clips.size(); ++clip_idx) {
    const ClipWords& clip = clips[clip_idx];
    if (clip.resampler().weights() != clips[0].resampler().weights() ||
        clip.resampler().layout().joint_count != clips[0].resampler().layout().joint_count) {
      return Status::InvalidArgument("word pool: clips of different skeletons or weights");
    }
    PoolClip pool_clip;
    pool_clip.archive_clip = static_cast<uint32_t>(clip_idx);
    pool_clip.word_count = clip.word_count();
    pool_clip.first_word_id = word_id;
    word_id += clip.word_count();
    pool_clips.push_back(pool_clip);
    data.push_back(MakeClipData(clip, clip.word_count(), options));
  }
  return Assemble(std::move(pool_clips), std::move(data), clips[0].resampler(), options);
}

Result<WordPool> WordPool::Build(const FrameFileReader& reader,
                                 const std::vector<float>& joint_weights,
                                 const WordPoolOptions& options) {
  MOTIF_RETURN_IF_ERROR(ValidateWordPoolOptions(options));
  MOTIF_ASSIGN_OR_RETURN(FrameResampler resampler,
                         FrameResampler::Create(reader.layout(), joint_weights));
  const size_t clip_count = reader.clips().size();
  std::vector<uint64_t> words(clip_count);
  std::vector<uint64_t> first_ids(clip_count);
  uint64_t total = 0;
  for (size_t clip_idx = 0; clip_idx < clip_count; ++clip_idx) {
    words[clip_idx] = ClipWordGrid(reader, clip_idx, options.words).word_count();
    first_ids[clip_idx] = total;
    total += words[clip_idx];
  }
  if (total == 0) {
    return Status::InvalidArgument(reader.path() + ": no clip is long enough for one word (" +
                                   std::to_string(options.words.word_frames) + " frames at " +
                                   std::to_string(options.words.word_fps) + " Hz)");
  }
  // Which clips, and how many of their words.
  std::vector<uint64_t> take(clip_count, 0);
  if (total <= options.max_words) {
    take = words;
  } else {
    std::vector<size_t> order(clip_count);
    std::iota(order.begin(), order.end(), 0);
    SplitMix64 random(options.seed ^ 0x706f6f6cull);  // "pool"
    for (size_t idx = clip_count - 1; idx > 0; --idx) {
      std::swap(order[idx], order[random.Below(idx + 1)]);
    }
    uint64_t remaining = options.max_words;
    for (size_t clip_idx : order) {
      if (remaining == 0) break;
      take[clip_idx] = std::min(words[clip_idx], remaining);
      remaining -= take[clip_idx];
    }
  }
  std::vector<PoolClip> clips;
  for (size_t clip_idx = 0; clip_idx < clip_count; ++clip_idx) {
    if (take[clip_idx] == 0) continue;
    PoolClip clip;
    clip.archive_clip = static_cast<uint32_t>(clip_idx);
    clip.word_count = take[clip_idx];
    clip.first_word_id = first_ids[clip_idx];
    clips.push_back(clip);
  }
  // Each task reads one clip and keeps only its compact words.
  std::vector<ClipData> data(clips.size());
  std::vector<Status> status(clips.size());
  std::atomic<uint64_t> done{0};
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, clips.size(), 1),
                      [&](const tbb::blocked_range<size_t>& range) {
                        for (size_t idx = range.begin(); idx != range.end(); ++idx) {
                          Result<ClipWords> clip = ClipWords::Read(reader, clips[idx].archive_clip,
                                                                   joint_weights, options.words);
                          if (!clip.ok()) {
                            status[idx] = clip.status();
                            continue;
                          }
                          data[idx] = MakeClipData(*clip, clips[idx].word_count, options);
                          const uint64_t finished = ++done;
                          if (options.progress) options.progress(finished, clips.size());
                        }
                      });
  });
  for (const Status& clip_status : status) MOTIF_RETURN_IF_ERROR(clip_status);
  return Assemble(std::move(clips), std::move(data), resampler, options);
}

const int16_t* WordPool::features(uint64_t word, uint32_t version) const {
  const size_t values = static_cast<size_t>(word_frames_) * 4 * weighted_joints_;
  return &features_[(word * versions_ + version) * values];
}

const float* WordPool::root_motion(uint64_t word, uint32_t version) const {
  const size_t values = static_cast<size_t>(word_frames_) * kRootMotionChannels;
  return &root_motion_[(word * versions_ + version) * values];
}

void WordPool::EncodeInput(uint64_t word, uint32_t version, float* out) const {
  EncodeWordInput(features(word, version), root_motion(word, version), word_frames_,
                  weighted_joints_, out);
}

uint32_t WordPool::input_channels() const { return WordInputChannels(weighted_joints_); }

}  // namespace motif
