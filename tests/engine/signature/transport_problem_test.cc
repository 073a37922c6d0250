#include "engine/signature/transport_problem.h"

#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>

namespace motif {
namespace {

int64_t Sum(const std::vector<int64_t>& values) {
  return std::accumulate(values.begin(), values.end(), int64_t{0});
}

TEST(QuantizeMasses, SumsExactlyToTheTotal) {
  const std::vector<double> weights = {1.0, 1.0, 1.0};  // thirds: every bin has a remainder
  std::vector<int64_t> units;
  QuantizeMasses(weights, 10.0 / 3.0, 10, &units);
  EXPECT_EQ(Sum(units), 10);
  // 3.33.. each: one unit to hand out, to the first bin (equal fractions: the lower bin).
  EXPECT_EQ(units, (std::vector<int64_t>{4, 3, 3}));
}

TEST(QuantizeMasses, LargestRemainderGetsTheUnit) {
  const std::vector<double> weights = {0.12, 0.47, 0.41};
  std::vector<int64_t> units;
  QuantizeMasses(weights, 10.0, 10, &units);  // 1.2, 4.7, 4.1 -> floors 1, 4, 4; .7 wins
  EXPECT_EQ(units, (std::vector<int64_t>{1, 5, 4}));
}

TEST(QuantizeMasses, EmptyBinsStayEmpty) {
  const std::vector<double> weights = {0.0, 1.0, 0.0, 2.0};
  std::vector<int64_t> units;
  QuantizeMasses(weights, kMassUnits / 3.0, kMassUnits, &units);
  EXPECT_EQ(Sum(units), kMassUnits);
  EXPECT_EQ(units[0], 0);
  EXPECT_EQ(units[2], 0);
}

TEST(BuildTransportProblem, KeepsOnlyBinsWithMass) {
  const std::vector<double> p = {0.0, 2.0, 0.0, 2.0};
  const std::vector<double> q = {1.0, 0.0, 0.0, 3.0};
  Eigen::MatrixXd ground = Eigen::MatrixXd::Constant(4, 4, 1.0);
  // Entries between bins without mass are never read: make them poison.
  ground.row(2).setConstant(std::numeric_limits<double>::quiet_NaN());
  ground.col(2).setConstant(std::numeric_limits<double>::quiet_NaN());
  TransportProblem problem;
  ASSERT_TRUE(BuildTransportProblem(p, q, ground, EmdMass::kNormalize, &problem).ok());
  EXPECT_EQ(problem.source_bins, (std::vector<uint32_t>{1, 3}));
  EXPECT_EQ(problem.sink_bins, (std::vector<uint32_t>{0, 3}));
  EXPECT_EQ(problem.supply, (std::vector<int64_t>{kMassUnits / 2, kMassUnits / 2}));
  EXPECT_EQ(problem.demand, (std::vector<int64_t>{kMassUnits / 4, kMassUnits / 4 * 3}));
  EXPECT_EQ(problem.moved_units, kMassUnits);
  EXPECT_EQ(problem.cost.size(), 4u);
}

TEST(BuildTransportProblem, PartialMassAddsADummyOnTheSmallerSide) {
  const std::vector<double> p = {1.0, 0.0};
  const std::vector<double> q = {1.0, 3.0};
  const Eigen::MatrixXd ground = (Eigen::MatrixXd(2, 2) << 0, 1, 1, 0).finished();
  TransportProblem problem;
  ASSERT_TRUE(BuildTransportProblem(p, q, ground, EmdMass::kPartial, &problem).ok());
  EXPECT_EQ(problem.source_bins, (std::vector<uint32_t>{0, kDummyBin}));
  EXPECT_EQ(problem.supply, (std::vector<int64_t>{kMassUnits / 4, kMassUnits / 4 * 3}));
  EXPECT_EQ(problem.demand, (std::vector<int64_t>{kMassUnits / 4, kMassUnits / 4 * 3}));
  EXPECT_EQ(problem.moved_units, kMassUnits / 4);
  EXPECT_EQ(problem.cost, (std::vector<double>{0, 1, 0, 0}));  // the dummy's row costs nothing
}

TEST(BuildTransportProblem, RejectsBadInput) {
  const Eigen::MatrixXd ground = Eigen::MatrixXd::Ones(2, 2);
  TransportProblem problem;
  const auto build = [&](std::vector<double> p, std::vector<double> q,
                         const Eigen::MatrixXd& matrix) {
    return BuildTransportProblem(p, q, matrix, EmdMass::kNormalize, &problem);
  };
  EXPECT_TRUE(build({1, 0}, {1, 0, 0}, ground).IsInvalidArgument());      // sizes
  EXPECT_TRUE(build({1, 0, 0}, {1, 0, 0}, ground).IsInvalidArgument());   // ground size
  EXPECT_TRUE(build({1, -0.5}, {1, 0}, ground).IsInvalidArgument());      // negative mass
  EXPECT_TRUE(build({1, NAN}, {1, 0}, ground).IsInvalidArgument());       // NaN mass
  EXPECT_TRUE(build({1, INFINITY}, {1, 0}, ground).IsInvalidArgument());  // infinite mass
  EXPECT_TRUE(build({0, 0}, {1, 0}, ground).IsInvalidArgument());         // no mass
  EXPECT_TRUE(build({1, 1}, {1, 1}, -ground).IsInvalidArgument());        // negative ground
  Eigen::MatrixXd infinite = ground;
  infinite(0, 1) = INFINITY;
  EXPECT_TRUE(build({1, 1}, {1, 1}, infinite).IsInvalidArgument());
  EXPECT_TRUE(build({1, 1}, {1, 1}, ground).ok());
}

}  // namespace
}  // namespace motif
