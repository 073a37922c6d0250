// WordStream against ClipWords' direct materialisation on small archives written to disk: the
// same words (info and bytes) whatever the batch size, block size or clip range; words never
// cross clips; the count per clip follows the formula; clips shorter than a word give none; a
// 30 fps archive resampled across block boundaries gives the exact 24 Hz rotations.
#include "engine/signature/word_stream.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "engine/signature/clip_words.h"
#include "tests/engine/signature/word_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::AxisMotion;

// Every word of the stream, in order, in one batch.
WordBatch StreamAll(const FrameFileReader& reader, const WordStreamOptions& options,
                    size_t* batches = nullptr) {
  WordBatch all;
  auto stream = WordStream::Create(reader, testing::JointWeightsOf(reader.skeleton()), options);
  EXPECT_TRUE(stream.ok()) << stream.status().ToString();
  if (!stream.ok()) return all;
  const size_t stride = reader.layout().stride();
  all.Reset(options.words.word_frames, (*stream)->resampler().feature_values(),
            options.keep_rows ? stride : 0);
  WordBatch batch;
  size_t count = 0;
  while (true) {
    Result<bool> more = (*stream)->Next(&batch);
    EXPECT_TRUE(more.ok()) << more.status().ToString();
    if (!more.ok() || !*more) break;
    ++count;
    EXPECT_GE(batch.size(), 1u);
    EXPECT_LE(batch.size(), options.batch_words);
    for (size_t word = 0; word < batch.size(); ++word) {
      const size_t out = all.Append(batch.info(word));
      std::memcpy(all.mutable_word(out), batch.word(word), all.word_values() * sizeof(int16_t));
      if (options.keep_rows) {
        std::memcpy(all.mutable_rows(out), batch.rows(word),
                    all.word_frames() * stride * sizeof(float));
      }
    }
  }
  EXPECT_EQ(all.size(), (*stream)->word_count());
  EXPECT_EQ((*stream)->words_done(), (*stream)->word_count());
  if (batches != nullptr) *batches = count;
  return all;
}

// Every word of clips [first_clip, end_clip), materialised clip by clip with ClipWords.
WordBatch MaterialiseAll(const FrameFileReader& reader, const WordOptions& options, bool keep_rows,
                         size_t first_clip = 0, size_t end_clip = SIZE_MAX) {
  WordBatch all;
  const size_t stride = reader.layout().stride();
  end_clip = std::min(end_clip, reader.clips().size());
  for (size_t clip_idx = first_clip; clip_idx < end_clip; ++clip_idx) {
    auto clip =
        ClipWords::Read(reader, clip_idx, testing::JointWeightsOf(reader.skeleton()), options);
    EXPECT_TRUE(clip.ok()) << clip.status().ToString();
    if (!clip.ok()) return all;
    WordBatch words;
    clip->AllWords(&words, keep_rows);
    if (all.word_frames() == 0) {
      all.Reset(options.word_frames, words.feature_values(), keep_rows ? stride : 0);
    }
    for (size_t word = 0; word < words.size(); ++word) {
      const size_t out = all.Append(words.info(word));
      std::memcpy(all.mutable_word(out), words.word(word), all.word_values() * sizeof(int16_t));
      if (keep_rows) {
        std::memcpy(all.mutable_rows(out), words.rows(word),
                    all.word_frames() * stride * sizeof(float));
      }
    }
  }
  return all;
}

void ExpectSameWords(const WordBatch& expected, const WordBatch& actual) {
  ASSERT_EQ(expected.size(), actual.size());
  ASSERT_EQ(expected.word_values(), actual.word_values());
  for (size_t word = 0; word < expected.size(); ++word) {
    ASSERT_EQ(expected.info(word), actual.info(word)) << "word " << word;
    ASSERT_EQ(std::memcmp(expected.word(word), actual.word(word),
                          expected.word_values() * sizeof(int16_t)),
              0)
        << "word " << word;
    if (expected.has_rows() && actual.has_rows()) {
      ASSERT_EQ(std::memcmp(expected.rows(word), actual.rows(word),
                            expected.word_frames() * expected.row_floats() * sizeof(float)),
                0)
          << "word " << word;
    }
  }
}

// A synthetic archive (about 6,000 frames in clips of 2 to 8 s) with short clips among them:
// 1 frame, 75 (one frame short of a word), 76 (exactly one word), 95, 96 (two words).
class WordStreamTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const testing::SynthClips synth = testing::MakeSynthClips(6000, 11);
    ASSERT_GE(synth.clips.size(), 3u);
    std::vector<ClipFrames> clips = synth.clips;
    const std::vector<uint64_t> short_lengths = {1, 75, 76, 95, 96};
    for (size_t idx = 0; idx < short_lengths.size(); ++idx) {
      ClipFrames piece = synth.clips[idx % synth.clips.size()];
      piece.info.name = "short";
      piece.info.name += std::to_string(short_lengths[idx]);
      piece.info.frame_count = short_lengths[idx];
      piece.rows.resize(short_lengths[idx] *
                        FrameLayout{static_cast<uint32_t>(synth.skeleton.joint_count())}.stride());
      // Interleave: short clips at the front, between long ones and at the end.
      clips.insert(clips.begin() + std::min(clips.size(), 2 * idx), piece);
    }
    FrameFileWriterOptions options;
    options.block_frames = 37;  // blocks straddle clips and words
    path_ = dir_.File("words.mfs");
    testing::WriteClips(path_, synth.skeleton, clips, 120.0, options);
    reader_ = testing::OpenArchive(path_);
    ASSERT_NE(reader_, nullptr);
  }

  testing::TempDir dir_;
  std::string path_;
  std::unique_ptr<FrameFileReader> reader_;
};

TEST_F(WordStreamTest, GivesTheSameWordsAsADirectMaterialisation) {
  WordStreamOptions options;
  options.batch_words = 7;
  options.keep_rows = true;
  size_t batches = 0;
  const WordBatch streamed = StreamAll(*reader_, options, &batches);
  const WordBatch materialised = MaterialiseAll(*reader_, options.words, true);
  EXPECT_GT(streamed.size(), 200u);
  EXPECT_EQ(batches, (streamed.size() + 6) / 7) << "full batches but the last";
  ExpectSameWords(materialised, streamed);
  // Without the rows, the same features.
  options.keep_rows = false;
  ExpectSameWords(materialised, StreamAll(*reader_, options));
}

TEST_F(WordStreamTest, BatchSizeDoesNotChangeTheWords) {
  WordStreamOptions options;
  options.batch_words = 1;
  const WordBatch one = StreamAll(*reader_, options);
  options.batch_words = 100000;
  size_t batches = 0;
  const WordBatch all = StreamAll(*reader_, options, &batches);
  EXPECT_EQ(batches, 1u);
  ExpectSameWords(one, all);
}

TEST_F(WordStreamTest, WordsNeverCrossClips) {
  const WordBatch words = StreamAll(*reader_, WordStreamOptions());
  const std::vector<ClipInfo>& clips = reader_->clips();
  for (size_t word = 0; word < words.size(); ++word) {
    const WordInfo& info = words.info(word);
    ASSERT_LT(info.clip_idx, clips.size());
    const ClipInfo& clip = clips[info.clip_idx];
    EXPECT_EQ(info.word_id, word) << "ids count the archive's words in order";
    EXPECT_GE(info.first_source_frame, clip.first_frame) << word;
    EXPECT_LE(info.end_source_frame, clip.first_frame + clip.frame_count) << word;
    EXPECT_EQ(info.end_source_frame - info.first_source_frame, 76u) << "at 120 fps";
    EXPECT_EQ(info.first_source_frame, clip.first_frame + 20 * info.word_idx);
    EXPECT_DOUBLE_EQ(info.start_seconds, info.word_idx / 6.0);
    if (word > 0) {
      const WordInfo& previous = words.info(word - 1);
      if (previous.clip_idx == info.clip_idx) {
        EXPECT_EQ(info.word_idx, previous.word_idx + 1);
      } else {
        EXPECT_LT(previous.clip_idx, info.clip_idx);
        EXPECT_EQ(info.word_idx, 0u);
      }
    }
  }
}

TEST_F(WordStreamTest, CountsWordsPerClipByTheFormula) {
  const WordBatch words = StreamAll(*reader_, WordStreamOptions());
  const std::vector<ClipInfo>& clips = reader_->clips();
  std::vector<uint64_t> per_clip(clips.size(), 0);
  for (const WordInfo& info : words.infos()) ++per_clip[info.clip_idx];
  uint64_t total = 0;
  for (size_t clip_idx = 0; clip_idx < clips.size(); ++clip_idx) {
    const uint64_t frames = clips[clip_idx].frame_count;
    const uint64_t samples = (frames - 1) / 5 + 1;
    const uint64_t expected = samples >= 16 ? (samples - 16) / 4 + 1 : 0;
    EXPECT_EQ(per_clip[clip_idx], expected) << clips[clip_idx].name << " (" << frames << ")";
    total += expected;
    if (clips[clip_idx].name == "short75" || clips[clip_idx].name == "short1") {
      EXPECT_EQ(per_clip[clip_idx], 0u);
    }
    if (clips[clip_idx].name == "short76") {
      EXPECT_EQ(per_clip[clip_idx], 1u);
    }
    if (clips[clip_idx].name == "short96") {
      EXPECT_EQ(per_clip[clip_idx], 2u);
    }
  }
  EXPECT_EQ(words.size(), total);
}

TEST_F(WordStreamTest, ClipRangeGivesThoseClipsWords) {
  WordStreamOptions options;
  options.first_clip = 2;
  options.clip_count = 4;
  options.batch_words = 5;
  const WordBatch part = StreamAll(*reader_, options);
  ExpectSameWords(MaterialiseAll(*reader_, options.words, false, 2, 6), part);
  ASSERT_FALSE(part.empty());
  // Ids are the archive's.
  const WordBatch all = StreamAll(*reader_, WordStreamOptions());
  size_t first = 0;
  while (all.info(first).clip_idx < 2) ++first;
  EXPECT_EQ(part.info(0).word_id, first);
  // A range past the end gives nothing.
  options.first_clip = reader_->clips().size();
  EXPECT_TRUE(StreamAll(*reader_, options).empty());
}

TEST_F(WordStreamTest, OtherWordShapes) {
  WordStreamOptions options;
  options.words.word_frames = 6;
  options.words.stride_frames = 9;  // gaps: samples in no word are skipped
  options.words.word_fps = 30;
  options.batch_words = 3;
  options.keep_rows = true;
  ExpectSameWords(MaterialiseAll(*reader_, options.words, true), StreamAll(*reader_, options));
  options.words.word_frames = 20;
  options.words.stride_frames = 1;
  options.words.word_fps = 120;  // the archive's rate: no resampling
  ExpectSameWords(MaterialiseAll(*reader_, options.words, true), StreamAll(*reader_, options));
}

TEST(WordStream, ResamplesA30FpsArchiveAcrossBlocks) {
  AxisMotion motion;
  motion.fps = 30;
  const Skeleton skeleton = testing::ChainSkeleton(motion.joint_count);
  testing::TempDir dir;
  const std::string path = dir.File("axis.mfs");
  FrameFileWriterOptions writer_options;
  writer_options.block_frames = 5;  // samples often interpolate across two blocks
  writer_options.lossless = true;
  testing::WriteClips(path, skeleton, {motion.Clip("a", 121), motion.Clip("b", 50)}, 30.0,
                      writer_options);
  auto reader = testing::OpenArchive(path);
  ASSERT_NE(reader, nullptr);
  WordStreamOptions options;
  options.keep_rows = true;
  const WordBatch words = StreamAll(*reader, options);
  // Clip a: 97 samples, 21 words; clip b: floor(49 * 0.8) + 1 = 40 samples, 7 words.
  ASSERT_EQ(words.size(), 28u);
  const FrameLayout layout{motion.joint_count};
  double worst = 0;
  for (size_t word = 0; word < words.size(); ++word) {
    const WordInfo& info = words.info(word);
    for (uint32_t frame = 0; frame < words.word_frames(); ++frame) {
      const double seconds = (info.first_sample + frame) / 24.0;
      const float* row = words.rows(word) + frame * layout.stride();
      for (uint32_t joint = 0; joint < motion.joint_count; ++joint) {
        worst = std::max(worst, testing::AngleTo(row + layout.quaternion_offset(joint),
                                                 motion.Rotation(joint, seconds)));
      }
      EXPECT_NEAR(row[layout.height_offset()], motion.Height(seconds), 1e-6);
    }
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_EQ(words.info(21).clip_idx, 1u);
  EXPECT_EQ(words.info(21).first_source_frame, 121u);
  EXPECT_EQ(words.info(21).end_source_frame, 121u + 20);  // t up to 18.75: frames 0..19
}

TEST(WordStream, ArchiveOfShortClipsHasNoWords) {
  AxisMotion motion;
  const Skeleton skeleton = testing::ChainSkeleton(motion.joint_count);
  testing::TempDir dir;
  const std::string path = dir.File("short.mfs");
  testing::WriteClips(path, skeleton, {motion.Clip("a", 75), motion.Clip("b", 1)}, 120.0);
  auto reader = testing::OpenArchive(path);
  ASSERT_NE(reader, nullptr);
  auto stream = WordStream::Create(*reader, testing::JointWeightsOf(skeleton));
  ASSERT_TRUE(stream.ok()) << stream.status().ToString();
  EXPECT_EQ((*stream)->word_count(), 0u);
  WordBatch batch;
  Result<bool> more = (*stream)->Next(&batch);
  ASSERT_TRUE(more.ok());
  EXPECT_FALSE(*more);
  EXPECT_TRUE(batch.empty());
}

TEST(WordStream, RejectsBadOptions) {
  AxisMotion motion;
  const Skeleton skeleton = testing::ChainSkeleton(motion.joint_count);
  testing::TempDir dir;
  const std::string path = dir.File("a.mfs");
  testing::WriteClips(path, skeleton, {motion.Clip("a", 200)}, 120.0);
  auto reader = testing::OpenArchive(path);
  ASSERT_NE(reader, nullptr);
  WordStreamOptions options;
  options.batch_words = 0;
  EXPECT_TRUE(WordStream::Create(*reader, testing::JointWeightsOf(skeleton), options)
                  .status()
                  .IsInvalidArgument());
  options = WordStreamOptions();
  options.words.stride_frames = 0;
  EXPECT_TRUE(WordStream::Create(*reader, testing::JointWeightsOf(skeleton), options)
                  .status()
                  .IsInvalidArgument());
  EXPECT_TRUE(WordStream::Create(*reader, {1, 1}).status().IsInvalidArgument());
  EXPECT_TRUE(
      ClipWords::Read(*reader, 1, testing::JointWeightsOf(skeleton)).status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif
