#include "engine/signature/transport_problem.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace motif {
namespace {

Status CheckHistogram(std::span<const double> histogram, const char* name, double* total) {
  double sum = 0;
  for (size_t bin = 0; bin < histogram.size(); ++bin) {
    const double mass = histogram[bin];
    if (!std::isfinite(mass) || mass < 0) {
      return Status::InvalidArgument(std::string("EMD: histogram ") + name + ": bin " +
                                     std::to_string(bin) + " has mass " + std::to_string(mass) +
                                     " (masses must be finite and >= 0)");
    }
    sum += mass;
  }
  if (!(sum > 0) || !std::isfinite(sum)) {
    return Status::InvalidArgument(std::string("EMD: histogram ") + name +
                                   " has no mass (or an infinite total)");
  }
  *total = sum;
  return Status::Ok();
}

// The bins with units, in ascending order, and their units.
void Support(const std::vector<int64_t>& units, std::vector<uint32_t>* bins,
             std::vector<int64_t>* masses) {
  bins->clear();
  masses->clear();
  for (size_t bin = 0; bin < units.size(); ++bin) {
    if (units[bin] > 0) {
      bins->push_back(static_cast<uint32_t>(bin));
      masses->push_back(units[bin]);
    }
  }
}

}  // namespace

void QuantizeMasses(std::span<const double> weights, double scale, int64_t total_units,
                    std::vector<int64_t>* units) {
  const size_t count = weights.size();
  units->assign(count, 0);
  std::vector<double> fraction(count, 0.0);
  int64_t floor_sum = 0;
  for (size_t bin = 0; bin < count; ++bin) {
    const double scaled = weights[bin] * scale;
    const double whole = std::floor(scaled);
    (*units)[bin] = static_cast<int64_t>(whole);
    fraction[bin] = scaled - whole;
    floor_sum += (*units)[bin];
  }
  // The floors sum to total_units minus fewer than `count` units, give or take the rounding of
  // `scale` (which can also overshoot): hand out, or take back, one unit per bin in the order of
  // the fractional parts, so the result is the same on every platform.
  int64_t deficit = total_units - floor_sum;
  if (deficit == 0) return;
  std::vector<uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  if (deficit > 0) {
    // Largest fraction first; only bins with weight can receive (ties: the lower bin).
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return fraction[a] > fraction[b]; });
    while (deficit > 0) {
      bool gave = false;
      for (uint32_t bin : order) {
        if (deficit == 0) break;
        if (weights[bin] > 0) {
          ++(*units)[bin];
          --deficit;
          gave = true;
        }
      }
      MOTIF_CHECK(gave);
    }
  } else {
    // Smallest fraction first; only bins with units can give one back.
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return fraction[a] < fraction[b]; });
    while (deficit < 0) {
      bool took = false;
      for (uint32_t bin : order) {
        if (deficit == 0) break;
        if ((*units)[bin] > 0) {
          --(*units)[bin];
          ++deficit;
          took = true;
        }
      }
      MOTIF_CHECK(took);
    }
  }
}

Status BuildTransportProblem(std::span<const double> p, std::span<const double> q,
                             const Eigen::Ref<const Eigen::MatrixXd>& ground, EmdMass mass,
                             TransportProblem* problem) {
  const size_t k = p.size();
  if (q.size() != k) {
    return Status::InvalidArgument("EMD: histograms of different sizes (" + std::to_string(k) +
                                   " and " + std::to_string(q.size()) + " bins)");
  }
  if (static_cast<size_t>(ground.rows()) != k || static_cast<size_t>(ground.cols()) != k) {
    return Status::InvalidArgument("EMD: the ground distance is " + std::to_string(ground.rows()) +
                                   " x " + std::to_string(ground.cols()) +
                                   ", the histograms have " + std::to_string(k) + " bins");
  }
  double p_total = 0;
  double q_total = 0;
  MOTIF_RETURN_IF_ERROR(CheckHistogram(p, "p", &p_total));
  MOTIF_RETURN_IF_ERROR(CheckHistogram(q, "q", &q_total));

  std::vector<int64_t> p_units;
  std::vector<int64_t> q_units;
  if (mass == EmdMass::kNormalize) {
    QuantizeMasses(p, static_cast<double>(kMassUnits) / p_total, kMassUnits, &p_units);
    QuantizeMasses(q, static_cast<double>(kMassUnits) / q_total, kMassUnits, &q_units);
  } else {
    // One common scale: the larger side totals kMassUnits, the smaller its share of it.
    const double larger = std::max(p_total, q_total);
    const double scale = static_cast<double>(kMassUnits) / larger;
    const auto side_units = [&](double total) {
      if (total == larger) return kMassUnits;
      return std::max<int64_t>(1, std::llround(total * scale));
    };
    QuantizeMasses(p, scale, side_units(p_total), &p_units);
    QuantizeMasses(q, scale, side_units(q_total), &q_units);
  }
  Support(p_units, &problem->source_bins, &problem->supply);
  Support(q_units, &problem->sink_bins, &problem->demand);

  const int64_t supply_units =
      std::accumulate(problem->supply.begin(), problem->supply.end(), int64_t{0});
  const int64_t demand_units =
      std::accumulate(problem->demand.begin(), problem->demand.end(), int64_t{0});
  problem->moved_units = std::min(supply_units, demand_units);
  // kPartial with unequal totals: a dummy on the smaller side takes the excess at no cost.
  if (supply_units < demand_units) {
    problem->source_bins.push_back(kDummyBin);
    problem->supply.push_back(demand_units - supply_units);
  } else if (demand_units < supply_units) {
    problem->sink_bins.push_back(kDummyBin);
    problem->demand.push_back(supply_units - demand_units);
  }

  const size_t sources = problem->source_count();
  const size_t sinks = problem->sink_count();
  problem->cost.assign(sources * sinks, 0.0);
  for (size_t source_idx = 0; source_idx < sources; ++source_idx) {
    const uint32_t from_bin = problem->source_bins[source_idx];
    if (from_bin == kDummyBin) continue;
    for (size_t sink_idx = 0; sink_idx < sinks; ++sink_idx) {
      const uint32_t to_bin = problem->sink_bins[sink_idx];
      if (to_bin == kDummyBin) continue;
      const double distance = ground(from_bin, to_bin);
      if (!std::isfinite(distance) || distance < 0) {
        return Status::InvalidArgument("EMD: ground distance (" + std::to_string(from_bin) + ", " +
                                       std::to_string(to_bin) + ") is " + std::to_string(distance) +
                                       " (must be finite and >= 0)");
      }
      problem->cost[source_idx * sinks + sink_idx] = distance;
    }
  }
  return Status::Ok();
}

}  // namespace motif
