// A motif's representative instance: its medoid, the instance with the least total time-warped
// distance d (warped_similarity.h) to the motif's other instances, and every instance's d to it.
// What a reader shows first of a motif, and how far each instance is from that typical one
// (motifs.json's "representative" and "distance", instances.csv's rank).
// d is measured for every pair of a motif's instances as the clustering measures an edge (the
// same samples and joint weights, the instance that starts first as the first argument), also
// when the clustering weighed pairs by shared frames: O(sum over motifs of instances^2 ·
// samples^2) pose distances, in parallel.
// Thread-safety: pure functions (the reader is safe to share).
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "engine/cluster/instance_samples.h"
#include "engine/cluster/motif_clusterer.h"
#include "engine/cluster/motif_instance.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

// The medoid of `count` items (count >= 1) of the symmetric row-major count × count matrix
// `distances`: the item whose row sums least, summed in index order; ties to the lowest index.
uint32_t MedoidIndex(const std::vector<double>& distances, size_t count);

// Sets each motif's `representative` (an index into its `instances`) and `distances` (d of each
// instance to the representative; exactly 0 for the representative itself). `instances` are the
// ids' frame ranges in `archive`; `samples` and `threads` as for WarpedDistances.
// InvalidArgument for an instance outside the archive; reader errors pass through.
Status FindRepresentatives(const FrameFileReader& archive,
                           const std::vector<MotifInstance>& instances, uint32_t samples,
                           int threads, std::vector<Motif>* motifs);

// The same on the instances' samples already read (ReadInstanceSamples over all of `instances`),
// which the clustering's warped distances measured too.
Status FindRepresentatives(const InstanceSamples& samples, int threads,
                           std::vector<Motif>* motifs);

}  // namespace motif
