// The search cache of `motifmine reindex` (engine/trellis/search_cache.h) and the features it
// extends: the pose features of an archive's earlier version extended with its appended frames
// are the features of the whole archive; a cache written and read back holds the same features,
// tables and thresholds; any damaged byte, a truncated file or another magic is refused.
#include "engine/trellis/search_cache.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "engine/lsh/hash_family.h"
#include "engine/synth/motion_synthesizer.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

bool SameFeatures(const PoseFeatures& a, const PoseFeatures& b) {
  return a.frame_count() == b.frame_count() && a.weights() == b.weights() &&
         a.joints() == b.joints() && a.clip_first_frames() == b.clip_first_frames() &&
         std::equal(a.values(), a.values() + a.memory_bytes() / 2, b.values());
}

class SearchCacheTest : public ::testing::Test {
 protected:
  // An archive committed twice: its first clips, then the others appended.
  void SetUp() override {
    archive_ = dir_.File("a.mfs");
    SynthOptions options;
    options.frames = 6000;
    options.motifs = 1;
    options.instances_min = 2;
    options.instances_max = 2;
    options.motif_seconds_max = 1;
    options.clip_seconds_min = 5;
    options.clip_seconds_max = 10;
    options.seed = 8;
    auto synthesizer = MotionSynthesizer::Create(options);
    ASSERT_TRUE(synthesizer.ok());
    std::vector<ClipFrames> clips;
    ASSERT_TRUE((*synthesizer)
                    ->Run([&](const ClipFrames& clip) {
                      clips.push_back(clip);
                      return Status::Ok();
                    })
                    .ok());
    ASSERT_GE(clips.size(), 3u);
    auto writer = FrameFileWriter::Create(archive_, (*synthesizer)->skeleton(), options.fps);
    ASSERT_TRUE(writer.ok());
    for (size_t idx = 0; idx < clips.size() / 2; ++idx) {
      ASSERT_TRUE((*writer)->AppendClip(clips[idx]).ok());
    }
    ASSERT_TRUE((*writer)->Commit().ok());
    writer->reset();
    auto first = FrameFileReader::Open(archive_);
    ASSERT_TRUE(first.ok());
    first_commit_ = {(*first)->summary().generation, (*first)->summary().file_bytes};
    auto append = FrameFileWriter::OpenForAppend(archive_);
    ASSERT_TRUE(append.ok());
    for (size_t idx = clips.size() / 2; idx < clips.size(); ++idx) {
      ASSERT_TRUE((*append)->AppendClip(clips[idx]).ok());
    }
    ASSERT_TRUE((*append)->Commit().ok());
  }

  std::vector<float> Weights(const FrameFileReader& reader) {
    auto weights = LoadDistanceWeights(reader.skeleton(), "");
    EXPECT_TRUE(weights.ok());
    return *weights;
  }

  testing::TempDir dir_;
  std::string archive_;
  std::pair<uint64_t, uint64_t> first_commit_;
};

TEST_F(SearchCacheTest, FeaturesOfTheEarlierVersionExtendedAreTheWholeArchives) {
  auto earlier = FrameFileReader::OpenCommit(archive_, first_commit_.first, first_commit_.second);
  auto now = FrameFileReader::Open(archive_);
  ASSERT_TRUE(earlier.ok() && now.ok()) << earlier.status().ToString();
  ASSERT_LT((*earlier)->frame_count(), (*now)->frame_count());
  auto old_features = PoseFeatures::FromArchive(**earlier, Weights(**earlier));
  auto all_features = PoseFeatures::FromArchive(**now, Weights(**now));
  ASSERT_TRUE(old_features.ok() && all_features.ok());
  auto extended = PoseFeatures::ExtendFromArchive(std::move(*old_features), **now, Weights(**now));
  ASSERT_TRUE(extended.ok()) << extended.status().ToString();
  EXPECT_TRUE(SameFeatures(*extended, *all_features));
  // Features of other weights are refused.
  std::vector<float> other = Weights(**now);
  other[1] = other[1] > 0 ? 0 : 1;
  auto refused = PoseFeatures::ExtendFromArchive(std::move(*extended), **now, other);
  EXPECT_FALSE(refused.ok());
}

TEST_F(SearchCacheTest, WrittenAndReadBackThenEveryDamageIsRefused) {
  auto now = FrameFileReader::Open(archive_);
  ASSERT_TRUE(now.ok());
  auto features = PoseFeatures::FromArchive(**now, Weights(**now));
  ASSERT_TRUE(features.ok());
  const HashFamily family = HashFamily::Draw(features->weights(), 3, 8, 0.2f, 5);
  auto index = LshIndex::Build(*features, family, 1000, 2, /*position_codes=*/true);
  ASSERT_TRUE(index.ok());
  std::vector<float> thresholds(features->frame_count());
  for (size_t idx = 0; idx < thresholds.size(); ++idx) thresholds[idx] = 0.001f * (idx % 997);
  const SearchCacheKey key{0x1234, 0x5678, "lsh tables=3 hashes=8"};
  const std::string path = dir_.File("search.msc");
  ASSERT_TRUE(WriteSearchCache(path, key, *features, &*index, 0xabcd, thresholds).ok());

  auto cache = ReadSearchCache(path);
  ASSERT_TRUE(cache.ok()) << cache.status().ToString();
  EXPECT_EQ(cache->key, key);
  EXPECT_TRUE(SameFeatures(cache->features, *features));
  ASSERT_EQ(cache->tables.size(), 3u);
  for (uint32_t table_idx = 0; table_idx < 3; ++table_idx) {
    const LshTableEntries& a = cache->tables[table_idx];
    const LshTableEntries& b = index->table(table_idx);
    EXPECT_TRUE(a.keys == b.keys && a.sort_values == b.sort_values && a.frames == b.frames &&
                a.codes == b.codes);
  }
  EXPECT_EQ(cache->trellis_identity, 0xabcdu);
  EXPECT_EQ(cache->thresholds, thresholds);

  // Without an index or thresholds.
  ASSERT_TRUE(WriteSearchCache(dir_.File("bare.msc"), {1, 2, ""}, *features, nullptr, 0, {}).ok());
  auto bare = ReadSearchCache(dir_.File("bare.msc"));
  ASSERT_TRUE(bare.ok()) << bare.status().ToString();
  EXPECT_TRUE(bare->tables.empty());
  EXPECT_EQ(bare->trellis_identity, 0u);

  // Damage: bytes flipped at spread offsets, the file truncated, another magic.
  const std::string bytes = ReadFileToString(path).value();
  for (size_t offset : {size_t{0}, size_t{9}, size_t{20}, size_t{80}, bytes.size() / 3,
                        bytes.size() / 2, bytes.size() - 9, bytes.size() - 1}) {
    std::string damaged = bytes;
    damaged[offset] = static_cast<char>(damaged[offset] ^ 0x10);
    ASSERT_TRUE(AtomicWriteFile(dir_.File("damaged.msc"), damaged).ok());
    auto read = ReadSearchCache(dir_.File("damaged.msc"));
    ASSERT_FALSE(read.ok()) << "offset " << offset;
    EXPECT_EQ(read.status().code(), Status::Code::kCorruption) << read.status().ToString();
  }
  ASSERT_TRUE(AtomicWriteFile(dir_.File("short.msc"), bytes.substr(0, bytes.size() - 100)).ok());
  EXPECT_EQ(ReadSearchCache(dir_.File("short.msc")).status().code(), Status::Code::kCorruption);
  EXPECT_EQ(ReadSearchCache(dir_.File("missing.msc")).status().code(), Status::Code::kNotFound);
}

}  // namespace
}  // namespace motif
