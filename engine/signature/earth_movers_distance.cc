#include "engine/signature/earth_movers_distance.h"

namespace motif {

Result<double> EarthMoversDistance::Distance(std::span<const double> p, std::span<const double> q,
                                             const Eigen::Ref<const Eigen::MatrixXd>& ground) {
  MOTIF_RETURN_IF_ERROR(BuildTransportProblem(p, q, ground, options_.mass, &problem_));
  simplex_.Solve(problem_, &plan_);
  return plan_.cost / static_cast<double>(problem_.moved_units);
}

Result<EmdSolution> EarthMoversDistance::Solve(std::span<const double> p, std::span<const double> q,
                                               const Eigen::Ref<const Eigen::MatrixXd>& ground) {
  MOTIF_RETURN_IF_ERROR(BuildTransportProblem(p, q, ground, options_.mass, &problem_));
  simplex_.Solve(problem_, &plan_);
  EmdSolution solution;
  const double moved = static_cast<double>(problem_.moved_units);
  solution.distance = plan_.cost / moved;
  solution.pivots = plan_.pivots;
  for (uint32_t bin : problem_.source_bins) solution.source_bins += bin != kDummyBin;
  for (uint32_t bin : problem_.sink_bins) solution.sink_bins += bin != kDummyBin;
  solution.flows.reserve(plan_.flows.size());
  for (const TransportFlow& flow : plan_.flows) {
    solution.flows.push_back({problem_.source_bins[flow.source], problem_.sink_bins[flow.sink],
                              static_cast<double>(flow.units) / moved});
  }
  return solution;
}

}  // namespace motif
