#include "engine/signature/transport_simplex.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "common/split_mix64.h"
#include "engine/signature/transport_reference.h"

namespace motif {
namespace {

enum class CostShape { kUniform, kSmallIntegers, kAllEqual, kEuclidean };

// A random balanced problem: `sources` x `sinks`, random integer masses summing to the same
// total on both sides, costs of the given shape (small integers and equal costs make many ties
// and degenerate pivots).
TransportProblem RandomProblem(uint32_t sources, uint32_t sinks, CostShape shape,
                               SplitMix64* random) {
  TransportProblem problem;
  const int64_t total = kMassUnits;
  const auto masses = [&](uint32_t count) {
    std::vector<double> weights(count);
    for (double& weight : weights) weight = 0.05 + random->Uniform();
    double sum = 0;
    for (double weight : weights) sum += weight;
    std::vector<int64_t> units;
    QuantizeMasses(weights, static_cast<double>(total) / sum, total, &units);
    return units;
  };
  problem.supply = masses(sources);
  problem.demand = masses(sinks);
  for (uint32_t bin = 0; bin < sources; ++bin) problem.source_bins.push_back(bin);
  for (uint32_t bin = 0; bin < sinks; ++bin) problem.sink_bins.push_back(bin);
  problem.moved_units = total;
  std::vector<double> source_x(sources), source_y(sources), sink_x(sinks), sink_y(sinks);
  for (uint32_t idx = 0; idx < sources; ++idx) {
    source_x[idx] = random->Uniform();
    source_y[idx] = random->Uniform();
  }
  for (uint32_t idx = 0; idx < sinks; ++idx) {
    sink_x[idx] = random->Uniform();
    sink_y[idx] = random->Uniform();
  }
  for (uint32_t source = 0; source < sources; ++source) {
    for (uint32_t sink = 0; sink < sinks; ++sink) {
      double cost = 0;
      switch (shape) {
        case CostShape::kUniform:
          cost = 10.0 * random->Uniform();
          break;
        case CostShape::kSmallIntegers:
          cost = static_cast<double>(random->Below(4));
          break;
        case CostShape::kAllEqual:
          cost = 2.5;
          break;
        case CostShape::kEuclidean:
          cost = std::hypot(source_x[source] - sink_x[sink], source_y[source] - sink_y[sink]);
          break;
      }
      problem.cost.push_back(cost);
    }
  }
  return problem;
}

// Every flow positive, and the flows meet every supply and demand exactly.
void ExpectFeasible(const TransportProblem& problem, const TransportPlan& plan) {
  std::vector<int64_t> shipped(problem.source_count(), 0);
  std::vector<int64_t> received(problem.sink_count(), 0);
  for (const TransportFlow& flow : plan.flows) {
    ASSERT_LT(flow.source, problem.source_count());
    ASSERT_LT(flow.sink, problem.sink_count());
    EXPECT_GT(flow.units, 0);
    shipped[flow.source] += flow.units;
    received[flow.sink] += flow.units;
  }
  EXPECT_EQ(shipped, problem.supply);
  EXPECT_EQ(received, problem.demand);
}

void CheckAgainstBoost(CostShape shape, uint64_t seed, uint32_t cases, uint32_t max_size) {
  SplitMix64 random(seed);
  TransportSimplex simplex;
  for (uint32_t case_idx = 0; case_idx < cases; ++case_idx) {
    const uint32_t sources = 1 + static_cast<uint32_t>(random.Below(max_size));
    const uint32_t sinks = 1 + static_cast<uint32_t>(random.Below(max_size));
    const TransportProblem problem = RandomProblem(sources, sinks, shape, &random);
    TransportPlan plan;
    TransportPlan reference;
    simplex.Solve(problem, &plan);
    SolveTransportWithBoost(problem, &reference);
    SCOPED_TRACE(testing::Message() << "case " << case_idx << ": " << sources << " x " << sinks);
    ExpectFeasible(problem, plan);
    ExpectFeasible(problem, reference);
    const double emd = plan.cost / static_cast<double>(problem.moved_units);
    const double expected = reference.cost / static_cast<double>(problem.moved_units);
    EXPECT_NEAR(emd, expected, 1e-9 * (1.0 + std::abs(expected)));
  }
}

TEST(TransportSimplex, MatchesBoostOnRandomCosts) {
  CheckAgainstBoost(CostShape::kUniform, 1, 300, 30);
}

TEST(TransportSimplex, MatchesBoostOnTiedIntegerCosts) {
  CheckAgainstBoost(CostShape::kSmallIntegers, 2, 300, 30);
}

TEST(TransportSimplex, MatchesBoostOnEqualCosts) {
  CheckAgainstBoost(CostShape::kAllEqual, 3, 50, 30);
}

TEST(TransportSimplex, MatchesBoostOnEuclideanCosts) {
  CheckAgainstBoost(CostShape::kEuclidean, 4, 300, 30);
}

TEST(TransportSimplex, MatchesBoostAtFullSupportOfAHundredMotifs) {
  SplitMix64 random(5);
  TransportSimplex simplex;
  for (CostShape shape : {CostShape::kUniform, CostShape::kEuclidean, CostShape::kSmallIntegers}) {
    const TransportProblem problem = RandomProblem(100, 100, shape, &random);
    TransportPlan plan;
    TransportPlan reference;
    simplex.Solve(problem, &plan);
    SolveTransportWithBoost(problem, &reference);
    ExpectFeasible(problem, plan);
    // A basic solution: at most sources + sinks - 1 positive flows.
    EXPECT_LE(plan.flows.size(), 199u);
    EXPECT_NEAR(plan.cost / kMassUnits, reference.cost / kMassUnits,
                1e-9 * (1.0 + reference.cost / kMassUnits));
  }
}

TEST(TransportSimplex, SolvesOneSourceOrOneSink) {
  TransportProblem problem;
  problem.source_bins = {0};
  problem.sink_bins = {0, 1, 2};
  problem.supply = {6};
  problem.demand = {1, 2, 3};
  problem.cost = {1.0, 2.0, 3.0};
  problem.moved_units = 6;
  TransportSimplex simplex;
  TransportPlan plan;
  simplex.Solve(problem, &plan);
  ExpectFeasible(problem, plan);
  EXPECT_DOUBLE_EQ(plan.cost, 1.0 * 1 + 2.0 * 2 + 3.0 * 3);
}

TEST(TransportSimplex, ReusesItsBuffersAcrossSizes) {
  SplitMix64 random(6);
  TransportSimplex simplex;
  for (uint32_t size : {40u, 3u, 25u, 1u, 40u}) {
    const TransportProblem problem = RandomProblem(size, size + 2, CostShape::kUniform, &random);
    TransportPlan plan;
    TransportPlan fresh_plan;
    simplex.Solve(problem, &plan);
    TransportSimplex fresh;
    fresh.Solve(problem, &fresh_plan);
    EXPECT_EQ(plan.cost, fresh_plan.cost);
    EXPECT_EQ(plan.pivots, fresh_plan.pivots);
  }
}

}  // namespace
}  // namespace motif
