#include "engine/cluster/motif_representatives.h"

#include <utility>

#include "engine/cluster/warped_similarity.h"

namespace motif {

uint32_t MedoidIndex(const std::vector<double>& distances, size_t count) {
  uint32_t best = 0;
  double best_total = 0;
  for (size_t row = 0; row < count; ++row) {
    double total = 0;
    for (size_t column = 0; column < count; ++column) total += distances[row * count + column];
    // Strictly less: a tie keeps the lower index.
    if (row == 0 || total < best_total) {
      best = static_cast<uint32_t>(row);
      best_total = total;
    }
  }
  return best;
}

namespace {

// Every pair within each motif, the one that starts first (the lower id: ids ascend by start
// within a motif) first, as in the graph.
std::vector<std::pair<uint32_t, uint32_t>> PairsWithinMotifs(const std::vector<Motif>& motifs) {
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (const Motif& motif : motifs) {
    for (size_t a = 0; a < motif.instances.size(); ++a) {
      for (size_t b = a + 1; b < motif.instances.size(); ++b) {
        pairs.emplace_back(motif.instances[a], motif.instances[b]);
      }
    }
  }
  return pairs;
}

// Each motif's medoid and distances from `measured`, the pairs of PairsWithinMotifs in order.
void SetRepresentatives(const std::vector<double>& measured, std::vector<Motif>* motifs) {
  size_t next = 0;
  for (Motif& motif : *motifs) {
    const size_t count = motif.instances.size();
    if (count == 0) continue;
    std::vector<double> matrix(count * count, 0.0);
    for (size_t a = 0; a < count; ++a) {
      for (size_t b = a + 1; b < count; ++b) {
        matrix[a * count + b] = matrix[b * count + a] = measured[next++];
      }
    }
    motif.representative = MedoidIndex(matrix, count);
    motif.distances.assign(matrix.begin() + motif.representative * count,
                           matrix.begin() + (motif.representative + 1) * count);
  }
}

}  // namespace

Status FindRepresentatives(const FrameFileReader& archive,
                           const std::vector<MotifInstance>& instances, uint32_t samples,
                           int threads, std::vector<Motif>* motifs) {
  MOTIF_ASSIGN_OR_RETURN(
      const std::vector<double> measured,
      WarpedDistances(archive, instances, PairsWithinMotifs(*motifs), samples, threads));
  SetRepresentatives(measured, motifs);
  return Status::Ok();
}

Status FindRepresentatives(const InstanceSamples& samples, int threads,
                           std::vector<Motif>* motifs) {
  MOTIF_ASSIGN_OR_RETURN(const std::vector<double> measured,
                         WarpedDistances(samples, PairsWithinMotifs(*motifs), threads));
  SetRepresentatives(measured, motifs);
  return Status::Ok();
}

}  // namespace motif
