#include "engine/words/take_segmentation.h"

#include <cmath>

#include <gtest/gtest.h>

#include "engine/signature/take_retrieval.h"
#include "tests/engine/words/words_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

constexpr uint64_t kPieceFrames = 600;  // 5 s at 120 fps

// Three motion classes, 4 clips of each (clip c of class c % 3), and one more clip "joined": 5 s of
// a further clip of class 0, then of class 1, then of class 2 (junctions at frames 600 and 1200).
// Words are built with small options.
struct JoinedArchive {
  std::string path;
  std::unique_ptr<FrameFileReader> reader;
  LoadedWords words;
  uint32_t joined = 0;
  std::vector<uint32_t> clip_labels;  // class per clip, kUnlabelled for the joined clip
};

JoinedArchive MakeJoinedArchive(const TempDir& dir) {
  ClassClips classes = MakeClassClips(3, 5, 5.0, 31);
  const size_t stride = FrameLayout{static_cast<uint32_t>(classes.skeleton.joint_count())}.stride();
  ClipFrames joined = classes.clips[0];
  joined.info.name = "joined";
  joined.info.source_path = "joined.bvh";
  joined.info.frame_count = 3 * kPieceFrames;
  joined.rows.clear();
  JoinedArchive archive;
  std::vector<ClipFrames> clips;
  for (size_t clip = 0; clip < classes.clips.size(); ++clip) {
    // The last clip of each class goes into the joined take, not the archive on its own.
    if (clip + 3 >= classes.clips.size()) {
      const std::vector<float>& rows = classes.clips[clip].rows;
      joined.rows.insert(joined.rows.end(), rows.begin(),
                         rows.begin() + static_cast<std::ptrdiff_t>(kPieceFrames * stride));
      continue;
    }
    clips.push_back(classes.clips[clip]);
    archive.clip_labels.push_back(static_cast<uint32_t>(classes.classes[clip]));
  }
  archive.joined = static_cast<uint32_t>(clips.size());
  clips.push_back(joined);
  archive.clip_labels.push_back(kUnlabelled);
  archive.path = dir.File("joined.mfs");
  WriteClips(archive.path, classes.skeleton, clips, 120.0);
  const WordsPaths paths = DefaultWordsPaths(archive.path);
  WordsOptions options = SmallWordsOptions(12);
  options.train.epochs = 4;
  EXPECT_TRUE(BuildWords(archive.path, paths, options).ok());
  archive.reader = OpenArchive(archive.path);
  auto words = LoadWords(*archive.reader, paths, false);
  EXPECT_TRUE(words.ok());
  archive.words = std::move(words.value());
  return archive;
}

// Boundaries and labels of a segmentation of the joined clip.
void ExpectThreePiecesNearTheJunctions(const SegmentedTake& take, bool labelled) {
  ASSERT_EQ(take.segments.size(), 3u);
  EXPECT_EQ(take.segments[0].start, 0u);
  EXPECT_NEAR(static_cast<double>(take.segments[1].start), 600.0, 60.0);
  EXPECT_NEAR(static_cast<double>(take.segments[2].start), 1200.0, 60.0);
  EXPECT_EQ(take.segments[2].end, 3 * kPieceFrames);
  for (uint32_t piece = 0; piece < 3; ++piece) {
    if (labelled) {
      EXPECT_EQ(take.segments[piece].label, piece);
    }
  }
  EXPECT_NE(take.segments[0].label, take.segments[1].label);
  EXPECT_NE(take.segments[1].label, take.segments[2].label);
  EXPECT_NE(take.segments[0].label, take.segments[2].label);
}

class TakeSegmentationTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    archive_ = new JoinedArchive(MakeJoinedArchive(*dir_));
  }
  static void TearDownTestSuite() {
    delete archive_;
    delete dir_;
  }
  static TempDir* dir_;
  static JoinedArchive* archive_;
};
TempDir* TakeSegmentationTest::dir_ = nullptr;
JoinedArchive* TakeSegmentationTest::archive_ = nullptr;

TEST_F(TakeSegmentationTest, SupervisedLabelsEachPieceOfAJoinedTakeWithItsClass) {
  const JoinedArchive& a = *archive_;
  const std::vector<std::string> names = {"class0", "class1", "class2"};
  for (const WindowSignature signature : {WindowSignature::kWords, WindowSignature::kMotifs}) {
    SCOPED_TRACE(WindowSignatureName(signature));
    const PoseFeatures* features = nullptr;
    SegmentOptions options;
    options.signature = signature;
    options.threads = 1;
    auto one =
        SegmentSupervised(*a.reader, a.words, {a.joined}, a.clip_labels, names, features, options);
    options.threads = 2;
    auto two =
        SegmentSupervised(*a.reader, a.words, {a.joined}, a.clip_labels, names, features, options);
    ASSERT_TRUE(one.ok() && two.ok()) << one.status().ToString();
    ASSERT_EQ(one->takes.size(), 1u);
    ExpectThreePiecesNearTheJunctions(one->takes[0], true);
    EXPECT_EQ(one->takes[0].word_labels, two->takes[0].word_labels);
    EXPECT_EQ(one->reference_takes, 12u);
    EXPECT_EQ(one->takes[0].words, a.words.signatures.clip_words[a.joined]);
    EXPECT_EQ(one->signature, WindowSignatureName(signature));
  }
}

TEST_F(TakeSegmentationTest, TheDtwBaselineLabelsThePiecesToo) {
  const JoinedArchive& a = *archive_;
  auto weights = LoadDistanceWeights(a.reader->skeleton(), "");
  ASSERT_TRUE(weights.ok());
  auto features = PoseFeatures::FromArchive(*a.reader, *weights);
  ASSERT_TRUE(features.ok());
  SegmentOptions options;
  auto result = SegmentSupervised(*a.reader, a.words, {a.joined}, a.clip_labels,
                                  {"class0", "class1", "class2"}, &*features, options);
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  EXPECT_EQ(result->distance, "dtw");
  ExpectThreePiecesNearTheJunctions(result->takes[0], true);
}

TEST_F(TakeSegmentationTest, LabelledTakesAreSegmentedWithoutVotingForThemselves) {
  const JoinedArchive& a = *archive_;
  // Clip 0 is labelled class 0; segmented, its own windows are left out and the other three
  // class-0 takes give it its label throughout.
  auto result = SegmentSupervised(*a.reader, a.words, {0}, a.clip_labels,
                                  {"class0", "class1", "class2"}, nullptr, SegmentOptions{});
  ASSERT_TRUE(result.ok());
  ASSERT_EQ(result->takes[0].segments.size(), 1u);
  EXPECT_EQ(result->takes[0].segments[0].label, 0u);
  // With only clip 0 labelled, clip 1 gets its label, and clip 0 itself none (nothing else
  // votes). With no label at all: an error, not a guess.
  std::vector<uint32_t> only_zero(a.clip_labels.size(), kUnlabelled);
  only_zero[0] = 0;
  auto nobody =
      SegmentSupervised(*a.reader, a.words, {1}, only_zero, {"class0"}, nullptr, SegmentOptions{});
  ASSERT_TRUE(nobody.ok());
  EXPECT_EQ(nobody->takes[0].segments[0].label, 0u);
  auto alone =
      SegmentSupervised(*a.reader, a.words, {0}, only_zero, {"class0"}, nullptr, SegmentOptions{});
  ASSERT_TRUE(alone.ok());
  EXPECT_EQ(alone->takes[0].segments[0].label, kUnlabelled);
  std::vector<uint32_t> none(a.clip_labels.size(), kUnlabelled);
  EXPECT_TRUE(SegmentSupervised(*a.reader, a.words, {0}, none, {}, nullptr, SegmentOptions{})
                  .status()
                  .IsInvalidArgument());
}

// The unsupervised result on the joined archive: the junctions found, like pieces grouped.
void ExpectJunctionsAndGroups(const JoinedArchive& a, const Result<Segmentation>& result,
                              const std::vector<uint32_t>& all) {
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  ASSERT_EQ(result->takes.size(), all.size());
  const SegmentedTake& joined = result->takes[a.joined];
  ExpectThreePiecesNearTheJunctions(joined, false);
  // Every single-class take is one segment, in the group of its class's piece of the joined take.
  for (uint32_t clip = 0; clip < a.joined; ++clip) {
    ASSERT_EQ(result->takes[clip].segments.size(), 1u) << a.reader->clips()[clip].name;
    EXPECT_EQ(result->takes[clip].segments[0].label, joined.segments[a.clip_labels[clip]].label)
        << a.reader->clips()[clip].name;
  }
  EXPECT_EQ(result->label_names.size(), 3u);
}

// With either signature (affinity profiles, the default, or the motifs' TF-IDF), and with any
// thread count.
TEST_F(TakeSegmentationTest, UnsupervisedFindsTheJunctionsAndGroupsLikePiecesTogether) {
  const JoinedArchive& a = *archive_;
  std::vector<uint32_t> all;
  for (uint32_t clip = 0; clip < a.reader->clips().size(); ++clip) all.push_back(clip);
  for (const WindowSignature signature : {WindowSignature::kWords, WindowSignature::kMotifs}) {
    SCOPED_TRACE(WindowSignatureName(signature));
    SegmentOptions options;
    options.signature = signature;
    ExpectJunctionsAndGroups(a, SegmentUnsupervised(*a.reader, a.words, all, options), all);
    options.threads = 1;
    auto one_thread = SegmentUnsupervised(*a.reader, a.words, all, options);
    ASSERT_TRUE(one_thread.ok());
    options.threads = 2;
    auto two_threads = SegmentUnsupervised(*a.reader, a.words, all, options);
    ASSERT_TRUE(two_threads.ok());
    for (size_t take = 0; take < all.size(); ++take) {
      EXPECT_EQ(one_thread->takes[take].word_labels, two_threads->takes[take].word_labels);
      const std::vector<double>& one = one_thread->takes[take].change_scores;
      const std::vector<double>& two = two_threads->takes[take].change_scores;
      ASSERT_EQ(one.size(), two.size());
      for (size_t b = 0; b < one.size(); ++b) {
        // The same bits, NaN (not scored) included.
        EXPECT_TRUE(one[b] == two[b] || (std::isnan(one[b]) && std::isnan(two[b]))) << b;
      }
    }
  }
}


TEST_F(TakeSegmentationTest, SegmentsJsonListsEverySegmentWithItsClipAndLabel) {
  const JoinedArchive& a = *archive_;
  auto result = SegmentSupervised(*a.reader, a.words, {a.joined}, a.clip_labels,
                                  {"class0", "class1", "class2"}, nullptr, SegmentOptions{});
  ASSERT_TRUE(result.ok());
  const nlohmann::json json = SegmentsJson(*result, *a.reader, "joined.mfs");
  ASSERT_EQ(json["segments"].size(), 3u);
  EXPECT_EQ(json["segments"][0]["clip"], "joined");
  EXPECT_EQ(json["segments"][0]["start"], 0);
  EXPECT_EQ(json["segments"][0]["label"], "class0");
  EXPECT_EQ(json["segments"][2]["end"], 3 * kPieceFrames);
  EXPECT_EQ(json["segments"][1]["start"], json["segments"][0]["end"]);
  EXPECT_EQ(json["mode"], "supervised");
  EXPECT_EQ(json["k"], 5);
  EXPECT_EQ(json["window"], 9);
  EXPECT_EQ(json["neighbours"], "windows");
}

}  // namespace
}  // namespace motif::testing
