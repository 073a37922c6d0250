// The Earth Mover's Distance between two motion signatures (Aristidou et al. 2018, section 5;
// Rubner, Tomasi & Guibas 2000): the least total cost of moving one histogram's mass onto the
// other's, where moving a unit from motif a to motif b costs ground(a, b), the distance between
// the two motifs' centroids (ground_distance.h). Which motif each bin is matters: swapping the
// values of two bins changes the distance unless their ground distances to everything agree. It
// is NOT a 1-D Wasserstein distance over the bin values, a mistake seen in public code.
//
//   EMD(p, q) = min_f  sum_ab f_ab ground(a, b) / sum_ab f_ab
//   subject to f_ab >= 0, sum_b f_ab <= p_a, sum_a f_ab <= q_b, sum_ab f_ab = min(|p|, |q|)
//
// with p and q first divided by their totals under EmdMass::kNormalize (the default: both then
// have unit mass and the constraints are equalities), or taken as they are under kPartial
// (transport_problem.h explains both). Only bins with mass enter the problem; the solver is the
// exact network simplex of transport_simplex.h. EMD(p, p) = 0 when ground has a zero diagonal, and
// under kNormalize the EMD is a metric on distributions whenever ground is a metric.
// Thread-safety: an object reuses its scratch buffers between calls; use one per thread.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "common/status.h"
#include "engine/signature/transport_problem.h"
#include "engine/signature/transport_simplex.h"

namespace motif {

struct EmdOptions {
  EmdMass mass = EmdMass::kNormalize;
};

// One positive flow of an optimal transport, between bins of p and q. mass is a fraction of the
// moved mass: the flows between real bins sum to 1. Under kPartial, flows from or to kDummyBin
// hold the excess of the larger histogram, which is not moved.
struct EmdFlow {
  uint32_t from_bin = 0;
  uint32_t to_bin = 0;
  double mass = 0;
};

struct EmdSolution {
  double distance = 0;
  std::vector<EmdFlow> flows;  // ordered by (from_bin, to_bin)
  uint64_t pivots = 0;         // network simplex pivots
  uint32_t source_bins = 0;    // bins with mass in p (the problem's size)
  uint32_t sink_bins = 0;      // bins with mass in q
};

class EarthMoversDistance {
 public:
  explicit EarthMoversDistance(EmdOptions options = {}) : options_(options) {}

  // The EMD between histograms `p` and `q` over the same k bins under `ground` (k x k, cost per
  // unit moved from bin a to bin b; only entries between bins with mass are read).
  // InvalidArgument: sizes that differ, a negative or non-finite mass, a histogram with no mass,
  // a negative or non-finite ground distance between bins with mass.
  Result<double> Distance(std::span<const double> p, std::span<const double> q,
                          const Eigen::Ref<const Eigen::MatrixXd>& ground);

  // The same, with an optimal transport plan. Same errors.
  Result<EmdSolution> Solve(std::span<const double> p, std::span<const double> q,
                            const Eigen::Ref<const Eigen::MatrixXd>& ground);

  const EmdOptions& options() const { return options_; }

 private:
  EmdOptions options_;
  TransportProblem problem_;
  TransportSimplex simplex_;
  TransportPlan plan_;
};

}  // namespace motif
