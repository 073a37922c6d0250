#include "engine/cluster/normalized_cut.h"

#include <algorithm>
#include <limits>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace motif {

namespace {

// A group and the best way found to cut it.
struct Group {
  std::vector<uint32_t> nodes;  // ids of the whole graph, ascending
  SimilarityGraph graph;        // induced on `nodes`, local ids
  bool proposed = false;
  double ncut = std::numeric_limits<double>::infinity();
  std::vector<std::vector<uint32_t>> parts;  // local ids; empty: cannot be cut
  uint64_t eigen_solves = 0;
  uint64_t sparse_solves = 0;
  uint64_t unconverged = 0;
  bool components_split = false;
};

void ProposeCut(Group* group, const NormalizedCutOptions& options) {
  group->proposed = true;
  std::vector<std::vector<uint32_t>> components = group->graph.ConnectedComponents();
  if (components.size() > 1) {
    group->ncut = 0;
    group->parts = std::move(components);
    group->components_split = true;
    return;
  }
  if (group->nodes.size() < 2 * static_cast<size_t>(options.min_group_size)) return;
  const FiedlerVector fiedler = ComputeFiedlerVector(group->graph, options.spectral);
  ++group->eigen_solves;
  if (fiedler.sparse) ++group->sparse_solves;
  if (fiedler.values.empty()) {
    ++group->unconverged;
    return;
  }
  TwoWayCut cut = BestSweepCut(group->graph, fiedler.values, options.min_group_size);
  if (cut.side_a.empty()) return;
  group->ncut = cut.ncut;
  group->parts = {std::move(cut.side_a), std::move(cut.side_b)};
}

// The parts of a cut group as new groups; parts below the minimum size are counted as dropped.
std::vector<Group> CutInto(Group& group, const NormalizedCutOptions& options,
                           NormalizedCutStats* stats) {
  std::vector<std::vector<uint32_t>> kept_parts;
  for (std::vector<uint32_t>& part : group.parts) {
    if (part.size() < options.min_group_size) {
      stats->dropped_nodes += part.size();
    } else {
      kept_parts.push_back(std::move(part));
    }
  }
  std::vector<SimilarityGraph> graphs = group.graph.InducedParts(kept_parts);
  std::vector<Group> children(kept_parts.size());
  for (size_t idx = 0; idx < kept_parts.size(); ++idx) {
    children[idx].nodes.reserve(kept_parts[idx].size());
    for (uint32_t local : kept_parts[idx]) children[idx].nodes.push_back(group.nodes[local]);
    children[idx].graph = std::move(graphs[idx]);
  }
  if (!group.components_split) ++stats->spectral_cuts;
  return children;
}

void ProposeAll(std::vector<Group>* groups, const NormalizedCutOptions& options,
                tbb::task_arena* arena, NormalizedCutStats* stats) {
  arena->execute([&] {
    tbb::parallel_for(size_t{0}, groups->size(), [&](size_t idx) {
      if (!(*groups)[idx].proposed) ProposeCut(&(*groups)[idx], options);
    });
  });
  for (Group& group : *groups) {  // counted once, when proposed
    stats->eigen_solves += group.eigen_solves;
    stats->sparse_solves += group.sparse_solves;
    stats->unconverged += group.unconverged;
    group.eigen_solves = group.sparse_solves = group.unconverged = 0;
  }
}

}  // namespace

std::vector<std::vector<uint32_t>> ClusterByNormalizedCut(const SimilarityGraph& graph,
                                                          const NormalizedCutOptions& options,
                                                          NormalizedCutStats* stats) {
  NormalizedCutStats local_stats;
  if (stats == nullptr) stats = &local_stats;
  *stats = NormalizedCutStats();
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);

  // The components, without an eigenvector: a group cut by components is exactly that.
  std::vector<std::vector<uint32_t>> components = graph.ConnectedComponents();
  stats->components = components.size();
  std::vector<std::vector<uint32_t>> kept_components;
  for (std::vector<uint32_t>& component : components) {
    if (component.size() < options.min_group_size) {
      stats->dropped_nodes += component.size();
    } else {
      kept_components.push_back(std::move(component));
    }
  }
  std::vector<SimilarityGraph> graphs = graph.InducedParts(kept_components);
  std::vector<Group> groups(kept_components.size());
  for (size_t idx = 0; idx < groups.size(); ++idx) {
    groups[idx].nodes = std::move(kept_components[idx]);
    groups[idx].graph = std::move(graphs[idx]);
  }

  std::vector<Group> done;
  if (options.groups == 0) {
    // Level by level: every open group is proposed a cut in parallel, then cut or finished.
    while (!groups.empty()) {
      ProposeAll(&groups, options, &arena, stats);
      std::vector<Group> next;
      for (Group& group : groups) {
        if (!group.parts.empty() && group.ncut < options.max_ncut) {
          for (Group& child : CutInto(group, options, stats)) next.push_back(std::move(child));
        } else {
          done.push_back(std::move(group));
        }
      }
      groups = std::move(next);
    }
  } else {
    ProposeAll(&groups, options, &arena, stats);
    while (groups.size() < options.groups) {
      // The cheapest cut, ties to the group with the smallest node.
      size_t best = groups.size();
      for (size_t idx = 0; idx < groups.size(); ++idx) {
        if (groups[idx].parts.empty()) continue;
        if (best == groups.size() || groups[idx].ncut < groups[best].ncut ||
            (groups[idx].ncut == groups[best].ncut &&
             groups[idx].nodes.front() < groups[best].nodes.front())) {
          best = idx;
        }
      }
      if (best == groups.size()) break;
      std::vector<Group> children = CutInto(groups[best], options, stats);
      groups.erase(groups.begin() + static_cast<ptrdiff_t>(best));
      for (Group& child : children) groups.push_back(std::move(child));
      ProposeAll(&groups, options, &arena, stats);
    }
    done = std::move(groups);
  }

  std::vector<std::vector<uint32_t>> result;
  result.reserve(done.size());
  for (Group& group : done) result.push_back(std::move(group.nodes));
  std::sort(result.begin(), result.end(),
            [](const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
              return a.front() < b.front();
            });
  return result;
}

}  // namespace motif
