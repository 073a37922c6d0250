#include "engine/words/take_classification.h"

#include <gtest/gtest.h>

#include "common/split_mix64.h"
#include "engine/signature/signature_matrix.h"
#include "engine/words/word_model.h"
#include "tests/engine/words/words_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif::testing {
namespace {

TEST(TakeClassification, SeparatedGroupsOfPointsAreFoundAndClassified) {
  // Three blobs of 6 points in the plane, far apart: distances are Euclidean.
  SplitMix64 random(8);
  const double centres[3][2] = {{0, 0}, {20, 0}, {0, 20}};
  Eigen::MatrixXd points(18, 2);
  std::vector<std::string> labels;
  for (int idx = 0; idx < 18; ++idx) {
    points(idx, 0) = centres[idx % 3][0] + random.Gaussian();
    points(idx, 1) = centres[idx % 3][1] + random.Gaussian();
    labels.push_back(idx == 17 ? "" : "blob" + std::to_string(idx % 3));  // one unlabelled
  }
  Eigen::MatrixXd d(18, 18);
  for (int a = 0; a < 18; ++a) {
    for (int b = 0; b < 18; ++b) d(a, b) = (points.row(a) - points.row(b)).norm();
  }
  ClassifyOptions options;
  options.dims = 2;
  options.top = 4;  // blob 2 has 5 labelled points: each has 4 labelled neighbours of its own
  auto result = ClassifyTakes(d, labels, options);
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  EXPECT_EQ(result->label_names, (std::vector<std::string>{"blob0", "blob1", "blob2"}));
  EXPECT_EQ(result->group_count, 3u);
  EXPECT_DOUBLE_EQ(result->adjusted_rand_index, 1.0);
  EXPECT_DOUBLE_EQ(result->purity, 1.0);
  EXPECT_EQ(result->knn.labelled, 17u);
  EXPECT_DOUBLE_EQ(result->knn.accuracy, 1.0);
  EXPECT_DOUBLE_EQ(result->precision_at_top, 1.0);
  EXPECT_EQ(result->labels[17], kUnlabelled);
  EXPECT_EQ(result->groups[17], result->groups[14]);  // the unlabelled point is still grouped
  for (int idx = 0; idx < 18; ++idx) result->names.push_back("take" + std::to_string(idx));
  const nlohmann::json json = ClassificationJson(*result, "x.mfs");
  EXPECT_EQ(json["supervised"]["accuracy"], 1.0);
  EXPECT_EQ(json["takes"].size(), 18u);
  EXPECT_TRUE(json["takes"][17]["label"].is_null());
  EXPECT_EQ(json["takes"][0]["nearest"].size(), 4u);
  EXPECT_EQ(json["takes"][0]["predicted"], "blob0");
  EXPECT_TRUE(
      ClassifyTakes(Eigen::MatrixXd::Zero(1, 1), {"a"}, options).status().IsInvalidArgument());
  EXPECT_TRUE(ClassifyTakes(d, {"a", "b"}, options).status().IsInvalidArgument());
}

TEST(TakeClassification, SignaturesSeparateTakesOfDistinctMotionClasses) {
  TempDir dir;
  const ClassClips classes = MakeClassClips(3, 5, 4.0, 12);
  const std::string archive = dir.File("classes.mfs");
  WriteClips(archive, classes.skeleton, classes.clips, 120.0);
  const WordsPaths paths = DefaultWordsPaths(archive);
  WordsOptions options = SmallWordsOptions(12);
  options.train.epochs = 4;
  auto built = BuildWords(archive, paths, options);
  ASSERT_TRUE(built.ok()) << built.status().ToString();
  auto reader = OpenArchive(archive);
  auto words = LoadWords(*reader, paths, false);
  ASSERT_TRUE(words.ok());
  std::vector<std::vector<double>> signatures;
  std::vector<std::string> labels;
  for (size_t clip = 0; clip < reader->clips().size(); ++clip) {
    signatures.push_back(words->ClipSignature(clip, false));
    labels.push_back("class" + std::to_string(classes.classes[clip]));
  }
  auto distances = SignatureDistanceMatrix(signatures, words->ground, 2);
  ASSERT_TRUE(distances.ok());
  ClassifyOptions classify;
  classify.top = 4;
  auto result = ClassifyTakes(*distances, labels, classify);
  ASSERT_TRUE(result.ok());

  EXPECT_DOUBLE_EQ(result->knn.accuracy, 1.0);
  EXPECT_DOUBLE_EQ(result->precision_at_top, 1.0);
  EXPECT_DOUBLE_EQ(result->adjusted_rand_index, 1.0);
}

}  // namespace
}  // namespace motif::testing
