// Instance similarity read back from the matching trellis (Meng et al. 2008, step 3: "the number
// of similar frames they share ... by tracing back to the trellis"), plus the path links.
//
// For instances a and b, shared(a -> b) = the frames t of a whose trellis column holds at least
// one frame of b. The similarity is
//     s(a, b) = min(1, max(shared(a -> b), shared(b -> a)) / min(|a|, |b|)),
// the largest fraction of the shorter instance that one side finds in the other: 1 for two
// occurrences of the same motif, and for a sub-motif inside a longer instance. Pairs below
// `min_similarity` are dropped, which keeps the graph sparse; the test is exact per direction
// (s >= tau iff some direction has shared >= tau · min(|a|, |b|)), so a direction below it is
// dropped as soon as its instance has been read. Linked pairs get `link_weight` on top.
//
// The trellis is streamed block by block in column order (blocks no instance touches are not
// decoded, distances are never decoded; each block's mapped pages are given back once decoded,
// so the file does not stay in the resident set). Per block, the instances that intersect it are
// processed in parallel; each thread counts into dense per-instance arrays (O(instances) a
// thread, so the hot loop is an array increment) and hands the instance one (other, count)
// entry per other instance hit. An instance's entries are reduced to its kept pairs as soon as
// its last column has been read, so memory is O(threads · instances + kept pairs + the entries
// of the instances open at once). Counts are integers and every list is sorted, so the graph
// is the same for any thread count.
// Thread-safety: pure function (the reader is safe to share).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "common/status.h"
#include "engine/cluster/motif_instance.h"
#include "engine/cluster/similarity_graph.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "motifmine/defaults.h"

namespace motif {

struct SimilarityOptions {
  double min_similarity =
      motifmine::defaults::kMinSimilarity;  // pairs below this (and not linked) get no edge
  double link_weight = 1.0;                 // added to linked pairs (similarity is at most 1)
  int threads = 0;                          // 0: all cores
  // Called after each decoded block with (columns done, columns to read).
  std::function<void(uint64_t, uint64_t)> progress;
};

struct SimilarityStats {
  uint64_t columns_read = 0;  // instance columns scanned (overlapping instances count twice)
  uint64_t blocks_decoded = 0;
  uint64_t neighbours_scanned = 0;
  uint64_t directed_pairs = 0;  // kept (a -> b) counts
  uint64_t similar_pairs = 0;   // pairs with s >= min_similarity
  uint64_t linked_pairs = 0;
  uint64_t edges = 0;  // in the graph
  double seconds = 0;
};

// `instances` sorted by start (as BuildInstances makes them), inside [0, trellis columns);
// links between ids of `instances`. InvalidArgument otherwise; Corruption from the trellis.
Result<SimilarityGraph> BuildSimilarityGraph(const TrellisFileReader& trellis,
                                             const std::vector<MotifInstance>& instances,
                                             const std::vector<InstanceLink>& links,
                                             const SimilarityOptions& options,
                                             SimilarityStats* stats = nullptr);

}  // namespace motif
