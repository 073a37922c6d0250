#include "engine/cluster/motif_clusterer.h"

#include <algorithm>
#include <chrono>

namespace motif {

namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

std::vector<Motif> RankMotifs(const std::vector<std::vector<uint32_t>>& groups,
                              const std::vector<MotifInstance>& instances) {
  std::vector<Motif> motifs;
  for (const std::vector<uint32_t>& group : groups) {
    if (group.size() < 2) continue;
    Motif motif;
    motif.instances = group;
    std::sort(motif.instances.begin(), motif.instances.end());
    for (uint32_t id : motif.instances) motif.total_frames += instances[id].length();
    motifs.push_back(std::move(motif));
  }
  std::sort(motifs.begin(), motifs.end(), [&](const Motif& a, const Motif& b) {
    if (a.total_frames != b.total_frames) return a.total_frames > b.total_frames;
    return a.instances.front() < b.instances.front();
  });
  return motifs;
}

Result<ClusterResult> ClusterMotifs(const std::vector<PathCandidate>& candidates,
                                    const TrellisFileReader& trellis,
                                    const ClusterOptions& options) {
  const uint64_t columns = trellis.column_count();
  for (size_t idx = 0; idx < candidates.size(); ++idx) {
    const PathCandidate& candidate = candidates[idx];
    if (candidate.top_end > columns || candidate.match_end > columns ||
        candidate.top_start > candidate.top_end || candidate.match_start > candidate.match_end) {
      return Status::InvalidArgument("path candidate " + std::to_string(idx) +
                                     " lies outside the trellis's " + std::to_string(columns) +
                                     " columns (does the paths file belong to this trellis?)");
    }
  }
  ClusterResult result;
  auto started = std::chrono::steady_clock::now();
  InstanceSet set = BuildInstances(candidates, options.instances);
  result.report.instance_stats = set.stats;
  result.report.instance_seconds = SecondsSince(started);

  SimilarityOptions similarity = options.similarity;
  similarity.threads = options.threads;
  if (options.progress) {
    similarity.progress = [&](uint64_t done, uint64_t total) {
      options.progress("similarity", done, total);
    };
  }
  MOTIF_ASSIGN_OR_RETURN(SimilarityGraph graph,
                         BuildSimilarityGraph(trellis, set.instances, set.links, similarity,
                                              &result.report.similarity_stats));

  started = std::chrono::steady_clock::now();
  NormalizedCutOptions cut = options.cut;
  cut.threads = options.threads;
  cut.spectral.seed = options.seed;
  const std::vector<std::vector<uint32_t>> groups =
      ClusterByNormalizedCut(graph, cut, &result.report.cut_stats);
  result.report.cut_seconds = SecondsSince(started);

  result.motifs = RankMotifs(groups, set.instances);
  std::vector<MotifInstance> clustered;
  for (const Motif& motif : result.motifs) {
    result.report.clustered_instances += motif.instances.size();
    for (uint32_t id : motif.instances) clustered.push_back(set.instances[id]);
  }
  std::sort(clustered.begin(), clustered.end(), [](const MotifInstance& a, const MotifInstance& b) {
    return a.start < b.start;
  });
  uint64_t covered_until = 0;
  for (const MotifInstance& instance : clustered) {
    const uint64_t from = std::max(instance.start, covered_until);
    if (instance.end > from) result.report.covered_frames += instance.end - from;
    covered_until = std::max(covered_until, instance.end);
  }
  result.instances = std::move(set.instances);
  result.links = std::move(set.links);
  return result;
}

}  // namespace motif
