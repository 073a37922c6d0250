// The transportation problem behind an Earth Mover's Distance (Rubner, Tomasi & Guibas, "The
// Earth Mover's Distance as a metric for image retrieval", IJCV 2000), in the form the solvers
// take: the bins with mass on each side, their masses as integers that balance exactly, and the
// ground distances between those bins. Built from two histograms over the same k motifs and the
// k x k ground-distance matrix (docs/design/signatures.md section 1).
//
// Masses. Two histograms may have different totals (a TF-IDF signature's total depends on the
// take). EmdMass::kNormalize, the default, divides each histogram by its own total: both carry
// unit mass and the EMD is the least cost of turning one distribution into the other. This is how
// Aristidou et al. 2018 use it (signatures are compared as distributions; their formula divides
// the cost by the total flow, which is 1 for unit-mass signatures). It is a metric whenever the
// ground distance is. EmdMass::kPartial is Rubner's general definition: the smaller total moves
// entirely, the larger only in part (a zero-cost dummy bin absorbs the excess), and the cost is
// divided by the mass moved. It equals kNormalize when the totals are equal; when they differ it
// is not a metric (it is 0 between a histogram and twice that histogram), so it is offered for
// comparison with Rubner's code, not as the signature distance.
//
// Integer units. The masses are scaled so that the larger side totals kMassUnits = 2^50 and are
// rounded by the largest-remainder method (ties to the lower bin), so supply and demand balance
// exactly and the network simplex never compares floating-point flows. Rounding moves at most
// 2^-50 of the mass per bin, at the precision of the doubles the histograms came in. Only bins
// with a non-zero number of units enter the problem.
// Thread-safety: plain data and a pure function.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "common/status.h"

namespace motif {

enum class EmdMass : uint8_t {
  kNormalize = 0,  // each histogram divided by its total (the default; a metric)
  kPartial = 1,    // Rubner 2000: min(totals) moved, cost / min(totals)
};

// The larger side's total in integer units (2^50: flows, sums and their products with a unit
// count stay exact in int64 and in a double's 53-bit mantissa).
inline constexpr int64_t kMassUnits = int64_t{1} << 50;

// A bin index meaning "the dummy bin" of EmdMass::kPartial.
inline constexpr uint32_t kDummyBin = 0xffffffffu;

struct TransportProblem {
  std::vector<uint32_t> source_bins;  // bins of p with mass, ascending (then kDummyBin if any)
  std::vector<uint32_t> sink_bins;    // bins of q with mass, ascending (then kDummyBin if any)
  std::vector<int64_t> supply;        // units per source, each > 0
  std::vector<int64_t> demand;        // units per sink, each > 0; sum(demand) == sum(supply)
  std::vector<double> cost;           // sources x sinks, row-major; 0 on a dummy's row or column
  int64_t moved_units = 0;            // the mass the cost is divided by (kNormalize: kMassUnits)

  size_t source_count() const { return supply.size(); }
  size_t sink_count() const { return demand.size(); }
};

// Builds the problem of moving histogram `p` onto histogram `q` (both of size k) under
// `ground` (k x k; ground(a, b) is the cost per unit of mass moved from bin a to bin b), into
// `problem` (its vectors are reused). Only the entries of `ground` between bins with mass are
// read.
// InvalidArgument: sizes that do not match, a negative, NaN or infinite mass, a histogram with
// no mass, a negative or non-finite ground distance between two bins with mass.
Status BuildTransportProblem(std::span<const double> p, std::span<const double> q,
                             const Eigen::Ref<const Eigen::MatrixXd>& ground, EmdMass mass,
                             TransportProblem* problem);

// Rounds `weights` (each >= 0, finite, sum > 0) scaled by `scale` to integers that sum to exactly
// `total_units` (largest remainder; ties to the lower index). Exposed for tests.
void QuantizeMasses(std::span<const double> weights, double scale, int64_t total_units,
                    std::vector<int64_t>* units);

}  // namespace motif
