#include "engine/signature/tf_idf.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace motif {
namespace {

// Four takes over three motifs:
//   take 0: 0 0 1    take 1: 1 1    take 2: 0 2    take 3: 1
// df = (2, 3, 1): motif 0 is in takes 0 and 2, motif 1 in takes 0, 1 and 3, motif 2 in take 2.
// idf(m) = ln((1 + 4) / (1 + df)) + 1 = ln(5/3) + 1, ln(5/4) + 1, ln(5/2) + 1.
const std::vector<std::vector<uint32_t>> kTakes = {{0, 0, 1}, {1, 1}, {0, 2}, {1}};

TEST(TfIdf, CountsEachTakeOncePerMotif) {
  Result<TfIdf> model = TfIdf::Fit(kTakes, 3);
  ASSERT_TRUE(model.ok()) << model.status().ToString();
  EXPECT_EQ(model->take_count(), 4u);
  EXPECT_EQ(model->motif_count(), 3u);
  EXPECT_EQ(model->document_frequencies(), (std::vector<uint64_t>{2, 3, 1}));
  EXPECT_DOUBLE_EQ(model->idf()[0], 1.5108256237659907);  // ln(5/3) + 1
  EXPECT_DOUBLE_EQ(model->idf()[1], 1.2231435513142097);  // ln(5/4) + 1
  EXPECT_DOUBLE_EQ(model->idf()[2], 1.916290731874155);   // ln(5/2) + 1
}

TEST(TfIdf, TakeSignatureIsTermFrequencyTimesIdf) {
  Result<TfIdf> model = TfIdf::Fit(kTakes, 3);
  ASSERT_TRUE(model.ok());
  // Take 0: tf = (2/3, 1/3, 0).
  Result<std::vector<double>> signature = model->Signature(kTakes[0]);
  ASSERT_TRUE(signature.ok());
  ASSERT_EQ(signature->size(), 3u);
  EXPECT_DOUBLE_EQ((*signature)[0], 1.0072170825106603);   // 2/3 * (ln(5/3) + 1)
  EXPECT_DOUBLE_EQ((*signature)[1], 0.40771451710473655);  // 1/3 * (ln(5/4) + 1)
  EXPECT_EQ((*signature)[2], 0.0);
}

TEST(TfIdf, WindowSignatureUsesTheArchiveIdf) {
  Result<TfIdf> model = TfIdf::Fit(kTakes, 3);
  ASSERT_TRUE(model.ok());
  // Any run of words, here one no take contains: tf = (1/4, 1/4, 1/2).
  const std::vector<uint32_t> window = {2, 2, 0, 1};
  Result<std::vector<double>> signature = model->Signature(window);
  ASSERT_TRUE(signature.ok());
  EXPECT_DOUBLE_EQ((*signature)[0], 0.25 * (std::log(5.0 / 3.0) + 1.0));
  EXPECT_DOUBLE_EQ((*signature)[1], 0.25 * (std::log(5.0 / 4.0) + 1.0));
  EXPECT_DOUBLE_EQ((*signature)[2], 0.5 * (std::log(5.0 / 2.0) + 1.0));
}

TEST(TfIdf, AMotifInEveryTakeStillWeighsOne) {
  // df = N: ln((1 + N) / (1 + N)) + 1 = 1, never 0 or negative, so a window made only of such
  // words keeps its mass.
  Result<TfIdf> model = TfIdf::Fit(std::vector<std::vector<uint32_t>>{{0, 1}, {0}, {0, 0}}, 2);
  ASSERT_TRUE(model.ok());
  EXPECT_EQ(model->idf()[0], 1.0);
  Result<std::vector<double>> signature = model->Signature(std::vector<uint32_t>{0, 0, 0});
  ASSERT_TRUE(signature.ok());
  EXPECT_EQ((*signature)[0], 1.0);
  EXPECT_EQ((*signature)[1], 0.0);
  EXPECT_DOUBLE_EQ(model->idf()[1], std::log(4.0 / 2.0) + 1.0);
}

TEST(TfIdf, AnUnusedMotifHasAFiniteIdf) {
  Result<TfIdf> model = TfIdf::FromDocumentFrequencies(4, {4, 0});
  ASSERT_TRUE(model.ok());
  EXPECT_EQ(model->idf()[0], 1.0);
  EXPECT_DOUBLE_EQ(model->idf()[1], std::log(5.0) + 1.0);  // 2.6094379124341005
  EXPECT_DOUBLE_EQ(TfIdf::InverseDocumentFrequency(4, 0), 2.6094379124341005);
}

TEST(TfIdf, TermFrequenciesAloneSumToOne) {
  Result<std::vector<double>> tf = TfIdf::TermFrequencies(std::vector<uint32_t>{3, 1, 3, 3}, 4);
  ASSERT_TRUE(tf.ok());
  EXPECT_EQ(*tf, (std::vector<double>{0.0, 0.25, 0.0, 0.75}));
}

TEST(TfIdf, EmptyTakesCountInN) {
  Result<TfIdf> model = TfIdf::Fit(std::vector<std::vector<uint32_t>>{{0}, {}, {}}, 1);
  ASSERT_TRUE(model.ok());
  EXPECT_EQ(model->take_count(), 3u);
  EXPECT_DOUBLE_EQ(model->idf()[0], std::log(4.0 / 2.0) + 1.0);
}

TEST(TfIdf, ReportsInvalidInput) {
  EXPECT_TRUE(TfIdf::Fit(kTakes, 0).status().IsInvalidArgument());
  EXPECT_TRUE(TfIdf::Fit(kTakes, 2).status().IsInvalidArgument());  // motif 2 >= 2
  EXPECT_TRUE(TfIdf::Fit(std::vector<std::vector<uint32_t>>{}, 3).status().IsInvalidArgument());
  EXPECT_TRUE(TfIdf::FromDocumentFrequencies(0, {0}).status().IsInvalidArgument());
  EXPECT_TRUE(TfIdf::FromDocumentFrequencies(2, {3}).status().IsInvalidArgument());
  EXPECT_TRUE(TfIdf::FromDocumentFrequencies(2, {}).status().IsInvalidArgument());
  Result<TfIdf> model = TfIdf::Fit(kTakes, 3);
  ASSERT_TRUE(model.ok());
  EXPECT_TRUE(model->Signature(std::vector<uint32_t>{}).status().IsInvalidArgument());
  EXPECT_TRUE(model->Signature(std::vector<uint32_t>{0, 3}).status().IsInvalidArgument());
}

}  // namespace
}  // namespace motif
