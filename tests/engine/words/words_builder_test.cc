#include "engine/words/words_builder.h"

#include <gtest/gtest.h>

#include "engine/embedding/embedding_file.h"
#include "engine/words/word_model.h"
#include "tests/engine/words/words_test_util.h"
#include "tests/testing/byte_files.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

class WordsBuilderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const SynthClips synth = MakeSynthClips(12000, 17);
    archive_ = dir_.File("a.mfs");
    WriteClips(archive_, synth.skeleton, synth.clips, 120.0);
  }
  WordsPaths PathsFor(const std::string& prefix) const {
    return DefaultWordsPaths(dir_.File(prefix + ".mfs"));
  }
  TempDir dir_;
  std::string archive_;
};

TEST_F(WordsBuilderTest, WritesTheThreeFilesAndReusesThem) {
  const WordsPaths paths = PathsFor("a");
  auto first = BuildWords(archive_, paths, SmallWordsOptions());
  ASSERT_TRUE(first.ok()) << first.status().ToString();
  EXPECT_FALSE(first->embedding_reused);
  EXPECT_EQ(first->epoch_loss.size(), 3u);
  EXPECT_GT(first->words, 500u);
  EXPECT_EQ(first->motifs, 10u);
  EXPECT_GT(first->accuracy.triplets, 0u);
  EXPECT_FALSE(FileExists(paths.embedding + ".checkpoint"));
  const std::string embedding = ReadBytes(paths.embedding);
  const std::string motifs = ReadBytes(paths.motifs);
  const std::string signatures = ReadBytes(paths.signatures);

  auto second = BuildWords(archive_, paths, SmallWordsOptions());
  ASSERT_TRUE(second.ok());
  EXPECT_TRUE(second->embedding_reused);
  EXPECT_TRUE(second->motifs_reused);
  EXPECT_TRUE(second->signatures_reused);
  EXPECT_EQ(ReadBytes(paths.embedding), embedding);
  EXPECT_EQ(ReadBytes(paths.signatures), signatures);

  // Another k: the embedding is kept, the motifs and signatures are made again.
  auto twelve = BuildWords(archive_, paths, SmallWordsOptions(12));
  ASSERT_TRUE(twelve.ok());
  EXPECT_TRUE(twelve->embedding_reused);
  EXPECT_FALSE(twelve->motifs_reused);
  EXPECT_NE(ReadBytes(paths.motifs), motifs);

  // What was written reads back and fits together.
  auto reader = OpenArchive(archive_);
  auto loaded = LoadWords(*reader, paths, true);
  ASSERT_TRUE(loaded.ok()) << loaded.status().ToString();
  EXPECT_EQ(loaded->motifs.motif_count(), 12u);
  EXPECT_EQ(loaded->signatures.word_motifs.size(), first->words);
  uint64_t sized = 0;
  for (uint64_t size : loaded->motifs.cluster_sizes) sized += size;
  EXPECT_EQ(sized, first->words);
  for (size_t clip = 0; clip < reader->clips().size(); ++clip) {
    if (loaded->signatures.clip_words[clip] == 0) continue;
    EXPECT_EQ(loaded->ClipSignature(clip, false),
              *loaded->tf_idf->Signature(loaded->ClipMotifs(clip)));
  }
}

TEST_F(WordsBuilderTest, FilesAreIdenticalForOneAndTwoThreads) {
  WordsOptions options = SmallWordsOptions();
  options.threads = 1;
  ASSERT_TRUE(BuildWords(archive_, PathsFor("one"), options).ok());
  options.threads = 2;
  ASSERT_TRUE(BuildWords(archive_, PathsFor("two"), options).ok());
  EXPECT_EQ(ReadBytes(PathsFor("one").embedding), ReadBytes(PathsFor("two").embedding));
  EXPECT_EQ(ReadBytes(PathsFor("one").motifs), ReadBytes(PathsFor("two").motifs));
  EXPECT_EQ(ReadBytes(PathsFor("one").signatures), ReadBytes(PathsFor("two").signatures));
}

TEST_F(WordsBuilderTest, AnInterruptedTrainingResumesToTheSameFiles) {
  ASSERT_TRUE(BuildWords(archive_, PathsFor("straight"), SmallWordsOptions()).ok());
  const WordsPaths paths = PathsFor("cut");
  WordsOptions options = SmallWordsOptions();
  options.after_epoch = [](uint32_t epochs) {
    return epochs == 2 ? Status::IOError("stopped after 2 epochs") : Status::Ok();
  };
  EXPECT_TRUE(BuildWords(archive_, paths, options).status().IsIOError());
  EXPECT_TRUE(FileExists(paths.embedding + ".checkpoint"));
  EXPECT_FALSE(FileExists(paths.embedding));
  options.after_epoch = nullptr;
  auto resumed = BuildWords(archive_, paths, options);
  ASSERT_TRUE(resumed.ok()) << resumed.status().ToString();
  EXPECT_EQ(resumed->resumed_from_epoch, 2u);
  EXPECT_EQ(ReadBytes(paths.embedding), ReadBytes(PathsFor("straight").embedding));
  EXPECT_EQ(ReadBytes(paths.signatures), ReadBytes(PathsFor("straight").signatures));
  EXPECT_FALSE(FileExists(paths.embedding + ".checkpoint"));
}

TEST_F(WordsBuilderTest, DamagedFilesAreMadeAgainOrRefused) {
  const WordsPaths paths = PathsFor("a");
  ASSERT_TRUE(BuildWords(archive_, paths, SmallWordsOptions()).ok());
  const std::string embedding = ReadBytes(paths.embedding);
  const std::string signatures = ReadBytes(paths.signatures);
  // A damaged signatures file: search and classify refuse it, naming the file.
  PatchByte(paths.signatures, signatures.size() - 3,
            static_cast<char>(signatures[signatures.size() - 3] ^ 0x40));
  auto reader = OpenArchive(archive_);
  auto loaded = LoadWords(*reader, paths, false);
  ASSERT_FALSE(loaded.ok());
  EXPECT_TRUE(loaded.status().IsCorruption()) << loaded.status().ToString();
  EXPECT_NE(loaded.status().message().find(paths.signatures), std::string::npos);
  // A damaged embedding: words trains it again (the same bytes: training is deterministic), and
  // rewrites the signatures.
  PatchByte(paths.embedding, 100, static_cast<char>(embedding[100] ^ 1));
  auto again = BuildWords(archive_, paths, SmallWordsOptions());
  ASSERT_TRUE(again.ok()) << again.status().ToString();
  EXPECT_FALSE(again->embedding_reused);
  EXPECT_EQ(ReadBytes(paths.embedding), embedding);
  EXPECT_EQ(ReadBytes(paths.signatures), signatures);
  // Missing files: NotFound with the hint.
  auto none = LoadWords(*reader, PathsFor("none"), false);
  EXPECT_TRUE(none.status().IsNotFound());
  EXPECT_NE(none.status().message().find("motifmine words"), std::string::npos);
}

TEST_F(WordsBuilderTest, AnEmbeddingFromElsewhereIsLoadedNotTrained) {
  ASSERT_TRUE(BuildWords(archive_, PathsFor("a"), SmallWordsOptions()).ok());
  const SynthClips other = MakeSynthClips(8000, 99);
  const std::string other_archive = dir_.File("b.mfs");
  WriteClips(other_archive, other.skeleton, other.clips, 120.0);
  WordsOptions options = SmallWordsOptions();
  options.embedding_in = PathsFor("a").embedding;
  auto loaded = BuildWords(other_archive, DefaultWordsPaths(other_archive), options);
  ASSERT_TRUE(loaded.ok()) << loaded.status().ToString();
  EXPECT_TRUE(loaded->embedding_loaded);
  EXPECT_FALSE(FileExists(DefaultWordsPaths(other_archive).embedding));
  EXPECT_TRUE(FileExists(DefaultWordsPaths(other_archive).signatures));
  // An embedding of another skeleton is refused.
  const ClassClips chain = MakeClassClips(2, 2, 3.0, 1);
  const std::string chain_archive = dir_.File("c.mfs");
  WriteClips(chain_archive, chain.skeleton, chain.clips, 120.0);
  options.motifs = 4;
  auto refused = BuildWords(chain_archive, DefaultWordsPaths(chain_archive), options);
  EXPECT_TRUE(refused.status().IsInvalidArgument()) << refused.status().ToString();
}

TEST_F(WordsBuilderTest, RefusesMoreMotifsThanWordsAndBadOptions) {
  WordsOptions options = SmallWordsOptions(100000);
  EXPECT_TRUE(BuildWords(archive_, PathsFor("a"), options).status().IsInvalidArgument());
  options = SmallWordsOptions(5000);
  auto too_many = BuildWords(archive_, PathsFor("a"), options);
  EXPECT_TRUE(too_many.status().IsInvalidArgument());
  EXPECT_NE(too_many.status().message().find("fewer than"), std::string::npos);
  options = SmallWordsOptions();
  options.words.word_frames = 0;
  EXPECT_TRUE(BuildWords(archive_, PathsFor("a"), options).status().IsInvalidArgument());
  EXPECT_TRUE(BuildWords(dir_.File("missing.mfs"), PathsFor("m"), SmallWordsOptions())
                  .status()
                  .IsNotFound());
}

}  // namespace
}  // namespace motif::testing
