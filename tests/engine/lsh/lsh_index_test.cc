// LshIndex and LshShardBuilder: every frame once per table, sorted tables, bucket lookup, and the
// same index for any thread count and shard size.
#include "engine/lsh/lsh_index.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <tuple>

#include "tests/engine/lsh/lsh_test_util.h"

namespace motif {
namespace {

class LshIndexTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    features_ = new PoseFeatures(testing::SyntheticFeatures(20000, 21));
  }
  static void TearDownTestSuite() {
    delete features_;
    features_ = nullptr;
  }
  static HashFamily Family() { return HashFamily::Draw(features_->weights(), 6, 12, 0.06f, 99); }
  static PoseFeatures* features_;
};

PoseFeatures* LshIndexTest::features_ = nullptr;

bool SameTables(const LshIndex& a, const LshIndex& b) {
  if (a.table_count() != b.table_count()) return false;
  for (uint32_t table_idx = 0; table_idx < a.table_count(); ++table_idx) {
    const LshTableEntries& x = a.table(table_idx);
    const LshTableEntries& y = b.table(table_idx);
    if (x.keys != y.keys || x.sort_values != y.sort_values || x.frames != y.frames ||
        x.codes != y.codes) {
      return false;
    }
  }
  return true;
}

TEST_F(LshIndexTest, EveryFrameOncePerTableInSortedOrder) {
  const HashFamily family = Family();
  auto index = LshIndex::Build(*features_, family, 4096, 2);
  ASSERT_TRUE(index.ok()) << index.status().ToString();
  ASSERT_EQ(index->table_count(), 6u);
  EXPECT_EQ(index->frame_count(), features_->frame_count());
  for (uint32_t table_idx = 0; table_idx < index->table_count(); ++table_idx) {
    const LshTableEntries& table = index->table(table_idx);
    ASSERT_EQ(table.size(), features_->frame_count());
    std::vector<uint32_t> frames = table.frames;
    std::sort(frames.begin(), frames.end());
    for (uint32_t frame_idx = 0; frame_idx < frames.size(); ++frame_idx) {
      ASSERT_EQ(frames[frame_idx], frame_idx) << "table " << table_idx;
    }
    for (size_t idx = 1; idx < table.size(); ++idx) {
      const auto before =
          std::make_tuple(table.keys[idx - 1], table.sort_values[idx - 1], table.frames[idx - 1]);
      const auto after =
          std::make_tuple(table.keys[idx], table.sort_values[idx], table.frames[idx]);
      ASSERT_LT(before, after) << "table " << table_idx << " entry " << idx;
    }
  }
}

TEST_F(LshIndexTest, EntriesCarryTheFramesHashes) {
  const HashFamily family = Family();
  auto index = LshIndex::Build(*features_, family, 1 << 16, 1);
  ASSERT_TRUE(index.ok());
  std::vector<float> embedding(family.embedding_dims());
  std::vector<float> projections(family.table_count() * (family.hashes_per_table() + 1));
  const uint32_t rows = family.hashes_per_table() + 1;
  for (uint32_t table_idx = 0; table_idx < index->table_count(); ++table_idx) {
    const LshTableEntries& table = index->table(table_idx);
    for (size_t idx = 0; idx < table.size(); idx += 97) {
      family.Embed(features_->frame(table.frames[idx]), embedding.data());
      family.Project(embedding.data(), projections.data());
      EXPECT_EQ(table.keys[idx], family.KeyOfCoordinates(&projections[table_idx * rows]));
      EXPECT_EQ(table.sort_values[idx],
                family.QuantiseSortValue(projections[table_idx * rows + rows - 1]));
      EXPECT_EQ(table.codes[idx], family.PositionCode(&projections[table_idx * rows]));
    }
  }
}

TEST_F(LshIndexTest, FindBucketReturnsExactlyTheFramesOfAKey) {
  const HashFamily family = Family();
  auto index = LshIndex::Build(*features_, family, 8192, 2);
  ASSERT_TRUE(index.ok());
  for (uint32_t table_idx = 0; table_idx < index->table_count(); ++table_idx) {
    const LshTableEntries& table = index->table(table_idx);
    std::map<uint32_t, uint32_t> counts;
    for (uint32_t key : table.keys) ++counts[key];
    for (const auto& [key, count] : counts) {
      const auto [begin, end] = index->FindBucket(table_idx, key);
      ASSERT_EQ(end - begin, count) << "table " << table_idx << " key " << key;
      EXPECT_EQ(table.keys[begin], key);
    }
    // A key that is not there.
    uint32_t missing = 12345;
    while (counts.count(missing)) ++missing;
    const auto [begin, end] = index->FindBucket(table_idx, missing);
    EXPECT_EQ(begin, end);
    const LshBucketStats stats = index->BucketStats(table_idx);
    EXPECT_EQ(stats.buckets, counts.size());
  }
}

TEST_F(LshIndexTest, ShardedBuildIsTheSameForAnyThreadCountAndShardSize) {
  const HashFamily family = Family();
  auto serial = LshIndex::Build(*features_, family, 1 << 20, 1);  // one shard
  auto two_threads = LshIndex::Build(*features_, family, 3000, 2);
  auto one_thread = LshIndex::Build(*features_, family, 3000, 1);
  auto small_shards = LshIndex::Build(*features_, family, 777, 2);
  ASSERT_TRUE(serial.ok() && two_threads.ok() && one_thread.ok() && small_shards.ok());
  EXPECT_TRUE(SameTables(*serial, *two_threads));
  EXPECT_TRUE(SameTables(*serial, *one_thread));
  EXPECT_TRUE(SameTables(*serial, *small_shards));
}

// The first `frames` frames of `features`.
PoseFeatures Prefix(const PoseFeatures& features, uint64_t frames) {
  std::vector<uint64_t> clips;
  for (uint64_t start : features.clip_first_frames()) {
    if (start < frames || start == 0) clips.push_back(start);
  }
  auto prefix = PoseFeatures::FromParts(frames, features.weights(), features.joints(), clips,
                                        features.values());
  EXPECT_TRUE(prefix.ok());
  return std::move(prefix.value());
}

TEST_F(LshIndexTest, AnIndexSavedAndExtendedWithNewFramesIsTheIndexOfAllFrames) {
  const HashFamily family = Family();
  auto full = LshIndex::Build(*features_, family, 3000, 2);
  ASSERT_TRUE(full.ok());
  for (bool codes : {false, true}) {
    auto whole = LshIndex::Build(*features_, family, 3000, 2, codes);
    ASSERT_TRUE(whole.ok());
    // Prefixes inside a shard, on a shard boundary, and empty; extended once or twice.
    for (uint64_t old_frames : {uint64_t{0}, uint64_t{4321}, uint64_t{9000}, uint64_t{19990}}) {
      SCOPED_TRACE("old frames " + std::to_string(old_frames) + (codes ? ", codes" : ""));
      const PoseFeatures prefix = Prefix(*features_, old_frames);
      auto built = LshIndex::Build(prefix, family, 3000, 2, codes);
      ASSERT_TRUE(built.ok());
      // Saved (its tables copied out) and loaded again, as the search cache does.
      std::vector<LshTableEntries> tables;
      for (uint32_t table_idx = 0; table_idx < built->table_count(); ++table_idx) {
        tables.push_back(built->table(table_idx));
      }
      auto loaded = LshIndex::FromTables(old_frames, std::move(tables), codes);
      ASSERT_TRUE(loaded.ok()) << loaded.status().ToString();
      const PoseFeatures middle = Prefix(*features_, (old_frames + 20000) / 2);
      ASSERT_TRUE(loaded->Extend(middle, family, 3000, 1).ok());
      ASSERT_TRUE(loaded->Extend(*features_, family, 3000, 2).ok());
      EXPECT_EQ(loaded->frame_count(), features_->frame_count());
      EXPECT_TRUE(SameTables(*loaded, *whole));
      // Its directory finds the buckets the built one finds.
      for (uint32_t probe = 0; probe < 200; ++probe) {
        const uint32_t key = whole->table(probe % 6).keys[probe * 97 % 20000];
        EXPECT_EQ(loaded->FindBucket(probe % 6, key), whole->FindBucket(probe % 6, key));
      }
    }
  }
}

TEST_F(LshIndexTest, SavedTablesOutOfOrderOrOfTheWrongSizeAreRefused) {
  auto built = LshIndex::Build(*features_, Family(), 3000, 2);
  ASSERT_TRUE(built.ok());
  std::vector<LshTableEntries> tables = {built->table(0), built->table(1)};
  ASSERT_NE(tables[1].keys[10], tables[1].keys[11000]);
  std::swap(tables[1].keys[10], tables[1].keys[11000]);
  EXPECT_FALSE(LshIndex::FromTables(features_->frame_count(), tables, false).ok());
  tables = {built->table(0)};
  tables[0].keys.pop_back();
  EXPECT_FALSE(LshIndex::FromTables(features_->frame_count(), tables, false).ok());
}

TEST_F(LshIndexTest, MemoryIsAboutFourteenBytesPerFramePerTable) {
  const HashFamily family = Family();
  auto index = LshIndex::Build(*features_, family, 1 << 16, 2);
  ASSERT_TRUE(index.ok());
  const double per_frame_per_table =
      static_cast<double>(index->memory_bytes()) / features_->frame_count() / index->table_count();
  // frame id 4, key 4, sort value 2, position code 4, directory ~0.25
  EXPECT_GE(per_frame_per_table, 14.0);
  EXPECT_LT(per_frame_per_table, 14.6);
}

TEST_F(LshIndexTest, RejectsZeroShardSize) {
  const HashFamily family = Family();
  auto index = LshIndex::Build(*features_, family, 0, 1);
  ASSERT_FALSE(index.ok());
  EXPECT_TRUE(index.status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif
