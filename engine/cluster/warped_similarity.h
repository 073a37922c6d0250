// Edge weights from the time-warped distance between two instances' motions.
//
// The shared-frames similarity (instance_similarity.h) says whether two instances have similar
// poses at all. At a radius that accepts every repetition of a movement it also accepts the
// neighbouring movements: a high and a middle punch of one take share most of their poses within
// 12 degrees a joint, and the normalized cut then sees one motif. How far apart two instances
// are as motions tells them apart: d(a, b), the mean pose distance along the cheapest time warp
// between them (dynamic time warping over at most `samples` evenly spaced frames of each).
//
// How far apart repetitions of one movement are depends on the movement and the performer
// (0.3-0.6 between a take's high punches, about 0.95 between a squat bounce and the next;
// docs/design/motif_quality.md), so no fixed width fits. Each instance gets its own scale
// (local scaling, Zelnik-Manor & Perona 2004): s(a) = d to its k-th nearest instance that shares
// no frame with it. An edge of the graph gets the weight exp(-d(a, b)^2 / (s(a) s(b))): two
// instances that are each other's nearest weigh exactly e^-1, and a movement twice as far away
// as an instance's own repetitions weighs e^-4 of it. An instance with no such neighbour uses
// fallback_scale · eps, and no scale is below floor_scale · eps. No pair gains an edge; a pair
// more than `max_scales` times the geometric mean of its two scales apart (weight below
// e^-(max_scales^2)) loses its edge: by the rule's own measure it is not one movement, and on real
// archives these edges are most of the graph and keep the normalized cut peeling one large
// component (docs/design/motif_quality.md, section 6). Cost: O(edges · samples^2) pose distances,
// from the SIMD kernel, in parallel; O(instances · samples) features. Thread-safety: pure
// function (the reader is safe to share).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "common/status.h"
#include "engine/cluster/instance_samples.h"
#include "engine/cluster/motif_instance.h"
#include "engine/cluster/similarity_graph.h"
#include "engine/distance/pose_features.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

struct WarpedSimilarityOptions {
  bool enabled = true;          // false: the graph's own weights (shared frames and links)
  uint32_t neighbours = 1;      // k of the local scale
  double fallback_scale = 0.5;  // × eps, for an instance without a non-overlapping neighbour
  // × eps: no scale is below this. Two instances closer than 3 degrees a joint differ by noise;
  // without a floor the farthest of three close copies was cut off as a motif of its own (the
  // inserted copies of docs/design/motif_quality.md, section 6).
  double floor_scale = 0.25;
  uint32_t samples = 32;  // frames of an instance compared, evenly spaced (at least 2)
  double max_scales = 3;  // pairs farther apart than this many scales lose their edge
  int threads = 0;        // 0: all cores
};

struct WarpedSimilarityStats {
  uint64_t edges = 0;          // of the graph given
  uint64_t dropped_edges = 0;  // farther apart than max_scales
  double mean_distance = 0;    // d over the edges
  double seconds = 0;
};

// d: the mean pose distance along the cheapest warping path between frames [a0, a1) and
// [b0, b1) of `features` (steps (1,0), (0,1), (1,1); ties keep the shorter path). Both ranges
// non-empty. O((a1 - a0)(b1 - b0)) time and memory.
double MeanWarpedDistance(const PoseFeatures& features, uint64_t a0, uint64_t a1, uint64_t b0,
                          uint64_t b1);

// d of each pair (a, b) of `instances` (ids into it; global frame ranges of `archive`), measured
// as ReweightByWarpedDistance measures an edge: `samples` (at least 2) evenly spaced frames of
// each, the skeleton's default joint weights, a's frames the first argument of
// MeanWarpedDistance. In parallel (threads 0: all cores); only the instances of some pair are
// read. InvalidArgument for an instance outside the archive; reader errors pass through.
Result<std::vector<double>> WarpedDistances(const FrameFileReader& archive,
                                            const std::vector<MotifInstance>& instances,
                                            const std::vector<std::pair<uint32_t, uint32_t>>& pairs,
                                            uint32_t samples, int threads);

// The same on samples already read (ReadInstanceSamples with `samples` as above): pairs of
// instance ids into them. InvalidArgument for a pair naming no instance.
Result<std::vector<double>> WarpedDistances(const InstanceSamples& samples,
                                            const std::vector<std::pair<uint32_t, uint32_t>>& pairs,
                                            int threads);

// `graph`'s nodes are `instances` (global frame ranges of `archive`); distances with the
// skeleton's default joint weights. InvalidArgument for an instance outside the archive or
// neighbours == 0; reader errors pass through.
Result<SimilarityGraph> ReweightByWarpedDistance(const FrameFileReader& archive,
                                                 const std::vector<MotifInstance>& instances,
                                                 const SimilarityGraph& graph, float eps,
                                                 const WarpedSimilarityOptions& options,
                                                 WarpedSimilarityStats* stats = nullptr);

// The same on `instances`' samples already read (ReadInstanceSamples with options.samples); the
// stats' seconds then exclude the reading.
Result<SimilarityGraph> ReweightByWarpedDistance(const InstanceSamples& samples,
                                                 const std::vector<MotifInstance>& instances,
                                                 const SimilarityGraph& graph, float eps,
                                                 const WarpedSimilarityOptions& options,
                                                 WarpedSimilarityStats* stats = nullptr);

}  // namespace motif
