#include "engine/cluster/motif_clusterer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>

#include "common/seconds_since.h"
#include "engine/cluster/instance_interval_index.h"
#include "engine/cluster/instance_samples.h"
#include "engine/cluster/motif_representatives.h"

namespace motif {

namespace {

// The length-weighted median of the group's instance lengths: the length of the instance that
// covers the group's middle frame when its instances are laid end to end from the longest. A
// plain median would follow the fragments when they outnumber the instances (a long motif with
// six 60-frame fragments of it and five instances).
uint64_t TypicalLength(const std::vector<uint32_t>& group,
                       const std::vector<MotifInstance>& instances) {
  std::vector<uint64_t> lengths;
  lengths.reserve(group.size());
  uint64_t total = 0;
  for (uint32_t id : group) {
    lengths.push_back(instances[id].length());
    total += lengths.back();
  }
  std::sort(lengths.begin(), lengths.end(), std::greater<>());
  uint64_t covered = 0;
  for (uint64_t length : lengths) {
    covered += length;
    if (2 * covered >= total) return length;
  }
  return lengths.back();
}

// The connected components of `nodes` (ascending) under the path links between them, each
// ascending, ordered by their smallest instance.
std::vector<std::vector<uint32_t>> LinkedComponents(
    const std::vector<uint32_t>& nodes, const std::vector<std::vector<uint32_t>>& linked) {
  std::vector<std::vector<uint32_t>> components;
  std::vector<bool> seen(nodes.size(), false);
  auto index_of = [&](uint32_t id) -> int64_t {
    auto it = std::lower_bound(nodes.begin(), nodes.end(), id);
    return it != nodes.end() && *it == id ? it - nodes.begin() : -1;
  };
  for (size_t first = 0; first < nodes.size(); ++first) {
    if (seen[first]) continue;
    std::vector<uint32_t> component;
    std::vector<size_t> stack = {first};
    seen[first] = true;
    while (!stack.empty()) {
      const uint32_t id = nodes[stack.back()];
      stack.pop_back();
      component.push_back(id);
      for (uint32_t other : linked[id]) {
        const int64_t at = index_of(other);
        if (at >= 0 && !seen[static_cast<size_t>(at)]) {
          seen[static_cast<size_t>(at)] = true;
          stack.push_back(static_cast<size_t>(at));
        }
      }
    }
    std::sort(component.begin(), component.end());
    components.push_back(std::move(component));
  }
  return components;
}

// A class split off a group needs this many instances to stand as a motif. Two are too few: two
// short stretches that each match part of the group's motif also match each other by chance (on
// the planted archives every such pair was background, every class of 3 or more a motif).
constexpr size_t kMinSplitOffInstances = 3;

// Appends to `out` the length classes of `group` (ascending): the instances within
// max_length_ratio of its typical length form one class; the others are split off, and among
// them only the instances joined by path links to one another stand as classes of their own
// (each link component of at least kMinSplitOffInstances, split the same way in turn). An instance
// that shares frames with the group but is linked only to the longer instances is a fragment of
// them and is dropped.
void SplitByLength(const std::vector<uint32_t>& group, const std::vector<MotifInstance>& instances,
                   const std::vector<std::vector<uint32_t>>& linked, double max_length_ratio,
                   std::vector<std::vector<uint32_t>>* out, uint64_t* dropped) {
  if (max_length_ratio <= 0 || group.size() < 2) {
    out->push_back(group);
    return;
  }
  const double typical = static_cast<double>(TypicalLength(group, instances));
  std::vector<uint32_t> kept;
  std::vector<uint32_t> split_off;
  for (uint32_t id : group) {
    const double length = static_cast<double>(instances[id].length());
    const bool typical_length =
        length * max_length_ratio >= typical && length <= typical * max_length_ratio;
    (typical_length ? kept : split_off).push_back(id);
  }
  out->push_back(std::move(kept));
  for (std::vector<uint32_t>& component : LinkedComponents(split_off, linked)) {
    if (component.size() < kMinSplitOffInstances) {
      *dropped += component.size();
    } else {
      SplitByLength(component, instances, linked, max_length_ratio, out, dropped);
    }
  }
}

// Two instances of one motif may share at most this fraction of the shorter one's frames.
constexpr double kNearCopyOverlap = 0.25;

// The class without near-copies: instances are taken from the one closest to the class's
// typical length (ties: the earlier), and one that overlaps an instance already taken by more
// than kNearCopyOverlap of the shorter is left out. Ascending ids.
std::vector<uint32_t> WithoutNearCopies(const std::vector<uint32_t>& ids,
                                        const std::vector<MotifInstance>& instances) {
  if (ids.size() < 2) return ids;
  const double typical = static_cast<double>(TypicalLength(ids, instances));
  std::vector<uint32_t> order = ids;
  auto distance = [&](uint32_t id) {
    return std::abs(static_cast<double>(instances[id].length()) - typical);
  };
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    if (distance(a) != distance(b)) return distance(a) < distance(b);
    return a < b;
  });
  std::vector<uint32_t> kept;
  for (uint32_t id : order) {
    const MotifInstance& candidate = instances[id];
    const bool near_copy = std::any_of(kept.begin(), kept.end(), [&](uint32_t other) {
      const uint64_t shorter = std::min(candidate.length(), instances[other].length());
      return static_cast<double>(OverlapFrames(candidate, instances[other])) >
             kNearCopyOverlap * static_cast<double>(shorter);
    });
    if (!near_copy) kept.push_back(id);
  }
  std::sort(kept.begin(), kept.end());
  return kept;
}

// Motifs in rank order without those that are parts of a better-ranked motif: every instance
// of theirs lies, for at least 3/4 of its frames, inside one instance of a motif kept before it
// (the first steps of a routine found as a motif of their own besides the whole routine).
std::vector<Motif> WithoutPartsOfBetterMotifs(std::vector<Motif> ranked,
                                              const std::vector<MotifInstance>& instances) {
  const InstanceIntervalIndex index(instances);
  std::vector<bool> in_kept_motif(instances.size(), false);
  std::vector<Motif> kept;
  for (Motif& motif : ranked) {
    const bool part = std::all_of(motif.instances.begin(), motif.instances.end(), [&](uint32_t id) {
      const MotifInstance& instance = instances[id];
      for (uint32_t other : index.Containing(instance.start + instance.length() / 2)) {
        if (in_kept_motif[other] &&
            4 * OverlapFrames(instance, instances[other]) >= 3 * instance.length()) {
          return true;
        }
      }
      return false;
    });
    if (part) continue;
    for (uint32_t id : motif.instances) in_kept_motif[id] = true;
    kept.push_back(std::move(motif));
  }
  return kept;
}

}  // namespace

std::vector<Motif> RankMotifs(const std::vector<std::vector<uint32_t>>& groups,
                              const std::vector<MotifInstance>& instances,
                              const std::vector<InstanceLink>& links, double max_length_ratio,
                              uint64_t* length_outliers) {
  std::vector<std::vector<uint32_t>> linked(instances.size());
  for (const InstanceLink& link : links) {
    linked[link.a].push_back(link.b);
    linked[link.b].push_back(link.a);
  }
  std::vector<std::vector<uint32_t>> classes;
  uint64_t dropped = 0;
  for (const std::vector<uint32_t>& group : groups) {
    std::vector<uint32_t> sorted = group;
    std::sort(sorted.begin(), sorted.end());
    SplitByLength(sorted, instances, linked, max_length_ratio, &classes, &dropped);
  }
  if (length_outliers != nullptr) *length_outliers = dropped;
  std::vector<Motif> motifs;
  for (std::vector<uint32_t>& instance_ids : classes) {
    Motif motif;
    motif.instances = WithoutNearCopies(instance_ids, instances);
    if (motif.instances.size() < 2) continue;
    for (uint32_t id : motif.instances) motif.total_frames += instances[id].length();
    motifs.push_back(std::move(motif));
  }
  std::sort(motifs.begin(), motifs.end(), [&](const Motif& a, const Motif& b) {
    if (a.score() != b.score()) return a.score() > b.score();
    return a.instances.front() < b.instances.front();
  });
  return WithoutPartsOfBetterMotifs(std::move(motifs), instances);
}

namespace {

// InvalidArgument for a candidate outside the trellis's columns (another trellis's paths).
Status CheckCandidatesInTrellis(const std::vector<PathCandidate>& candidates, uint64_t columns) {
  for (size_t idx = 0; idx < candidates.size(); ++idx) {
    const PathCandidate& candidate = candidates[idx];
    if (candidate.top_end > columns || candidate.match_end > columns ||
        candidate.top_start > candidate.top_end || candidate.match_start > candidate.match_end) {
      return Status::InvalidArgument("path candidate " + std::to_string(idx) +
                                     " lies outside the trellis's " + std::to_string(columns) +
                                     " columns (does the paths file belong to this trellis?)");
    }
  }
  return Status::Ok();
}

// The pauses of the archive near the candidates' non-empty segments.
Result<std::vector<MotifInstance>> PausesNearCandidates(
    const FrameFileReader& archive, const PauseOptions& pauses,
    const std::vector<PathCandidate>& candidates, int threads) {
  std::vector<MotifInstance> segments;
  segments.reserve(2 * candidates.size());
  for (const PathCandidate& candidate : candidates) {
    if (candidate.top_end > candidate.top_start) {
      segments.push_back({candidate.top_start, candidate.top_end});
    }
    if (candidate.match_end > candidate.match_start) {
      segments.push_back({candidate.match_start, candidate.match_end});
    }
  }
  return FindPausesNear(archive, pauses, std::move(segments), threads);
}

// Frames of the archive in some instance of a motif (overlaps counted once).
uint64_t CoveredByMotifs(const std::vector<Motif>& motifs,
                         const std::vector<MotifInstance>& instances) {
  std::vector<MotifInstance> clustered;
  for (const Motif& motif : motifs) {
    for (uint32_t id : motif.instances) clustered.push_back(instances[id]);
  }
  std::sort(clustered.begin(), clustered.end(),
            [](const MotifInstance& a, const MotifInstance& b) { return a.start < b.start; });
  uint64_t covered_frames = 0;
  uint64_t covered_until = 0;
  for (const MotifInstance& instance : clustered) {
    const uint64_t from = std::max(instance.start, covered_until);
    if (instance.end > from) covered_frames += instance.end - from;
    covered_until = std::max(covered_until, instance.end);
  }
  return covered_frames;
}

// The instance graph: shared similar frames from the trellis, reweighted by the instances'
// time-warped distance when their samples are given.
Result<SimilarityGraph> InstanceGraph(const TrellisFileReader& trellis, const InstanceSet& set,
                                      const InstanceSamples* samples,
                                      const ClusterOptions& options, ClusterReport* report) {
  SimilarityOptions similarity = options.similarity;
  similarity.threads = options.threads;
  if (options.progress) {
    similarity.progress = [&](uint64_t done, uint64_t total) {
      options.progress("similarity", done, total);
    };
  }
  MOTIF_ASSIGN_OR_RETURN(SimilarityGraph graph,
                         BuildSimilarityGraph(trellis, set.instances, set.links, similarity,
                                              &report->similarity_stats));
  if (samples != nullptr) {
    WarpedSimilarityOptions warped = options.warped;
    warped.threads = options.threads;
    MOTIF_ASSIGN_OR_RETURN(
        graph, ReweightByWarpedDistance(*samples, set.instances, graph, trellis.params().eps,
                                        warped, &report->warped_stats));
  }
  return graph;
}

}  // namespace

Result<ClusterResult> ClusterMotifs(const std::vector<PathCandidate>& candidates,
                                    const TrellisFileReader& trellis,
                                    const ClusterOptions& options) {
  MOTIF_RETURN_IF_ERROR(CheckCandidatesInTrellis(candidates, trellis.column_count()));
  ClusterResult result;
  auto started = std::chrono::steady_clock::now();
  InstanceOptions instance_options = options.instances;
  if (options.archive != nullptr) {
    MOTIF_ASSIGN_OR_RETURN(instance_options.pauses,
                           PausesNearCandidates(*options.archive, options.pauses, candidates,
                                                options.threads));
  }
  result.report.pauses = instance_options.pauses.size();
  InstanceSet set = BuildInstances(candidates, instance_options);
  result.report.instance_stats = set.stats;
  result.report.instance_seconds = SecondsSince(started);
  // What the warped distances, the held poses and the representatives read of the instances.
  std::optional<InstanceSamples> samples;
  if (options.archive != nullptr) {
    started = std::chrono::steady_clock::now();
    MOTIF_ASSIGN_OR_RETURN(samples, ReadInstanceSamples(*options.archive, set.instances,
                                                        std::max(options.warped.samples, 2u),
                                                        trellis.params().eps, options.threads));
    result.report.sample_seconds = SecondsSince(started);
  }
  MOTIF_ASSIGN_OR_RETURN(SimilarityGraph graph,
                         InstanceGraph(trellis, set, samples ? &*samples : nullptr, options,
                                       &result.report));

  started = std::chrono::steady_clock::now();
  NormalizedCutOptions cut = options.cut;
  cut.threads = options.threads;
  cut.spectral.seed = options.seed;
  std::vector<std::vector<uint32_t>> groups =
      ClusterByNormalizedCut(graph, cut, &result.report.cut_stats);
  result.report.cut_seconds = SecondsSince(started);
  if (samples) {
    // Held poses (the body does not move for the whole instance) are never motif instances.
    for (std::vector<uint32_t>& group : groups) {
      std::erase_if(group, [&](uint32_t id) { return samples->held[id] != 0; });
    }
    result.report.held_poses = std::count(samples->held.begin(), samples->held.end(), 1);
  }

  result.motifs = RankMotifs(groups, set.instances, set.links, options.max_length_ratio,
                             &result.report.length_outliers);
  for (const Motif& motif : result.motifs) {
    result.report.clustered_instances += motif.instances.size();
  }
  result.report.covered_frames = CoveredByMotifs(result.motifs, set.instances);
  if (samples) {
    started = std::chrono::steady_clock::now();
    MOTIF_RETURN_IF_ERROR(FindRepresentatives(*samples, options.threads, &result.motifs));
    result.report.representative_seconds = SecondsSince(started);
  }
  result.instances = std::move(set.instances);
  result.links = std::move(set.links);
  return result;
}

}  // namespace motif
