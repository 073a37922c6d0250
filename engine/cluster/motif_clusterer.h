// ClusterMotifs: the clustering step of motif mining (Meng et al. 2008, step 3), from the path
// grower's candidates to ranked motifs:
//   candidates -> instances (instance_builder.h: longest path per root, 3/4-overlap merge, links)
//   -> similarity graph (instance_similarity.h: shared similar frames read back from the trellis,
//      plus the links) -> groups (normalized_cut.h) -> motifs, most important first, each with
//      its representative instance when the archive is given (motif_representatives.h).
// A motif's importance is Motif::score(), (instances - 1) × mean length; ties go to the motif that
// starts first. Two instances of one motif never share more than a quarter of the shorter: of
// such near-copies the one closer to the motif's typical length stays. A motif lying inside a
// better-ranked one is not listed. Its instances are listed by position.
// Instances of one motif differ in duration by a time warp, so each normalized-cut group is split
// by length first: the instances within max_length_ratio of the group's typical length (the
// length-weighted median) stay; the others are split off. A split-off instance path-linked to
// other split-off instances forms a motif with them (a short motif grouped with a long one that
// contains similar poses); one linked only to the group's instances is a fragment of them (a
// short stretch that matches part of the motif) and is dropped. A class of fewer than two
// instances is no motif.
// Thread-safety: one call per thread; the reader may be shared.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/cluster/instance_builder.h"
#include "engine/cluster/instance_similarity.h"
#include "engine/cluster/motif_instance.h"
#include "engine/cluster/normalized_cut.h"
#include "engine/cluster/pauses.h"
#include "engine/cluster/warped_similarity.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/paths_file/path_candidate.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "motifmine/defaults.h"

namespace motif {

struct ClusterOptions {
  InstanceOptions instances;
  SimilarityOptions similarity;  // its threads and progress are set from the fields below
  NormalizedCutOptions cut;      // its threads and seed are set from the fields below
  // With the archive set: edge weights from the instances' time-warped distance.
  WarpedSimilarityOptions warped;  // its threads are set from the field below
  // Keep an instance in its motif only when typical / r <= length <= typical * r, typical being
  // the length-weighted median of the group's lengths; 0 keeps every instance. Warps of 0.7-1.4x
  // differ by 2x at most; 3 leaves room for a typical length pulled down by split instances
  // (2 dropped a whole planted instance on one archive), while the fragments seen are 4-10x
  // shorter than their motif (60-90 frames against 300-800).
  double max_length_ratio = motifmine::defaults::kMaxLengthRatio;
  // With the archive set: instances are cut at the archive's pauses (pauses.h); max_speed 0
  // cuts nothing.
  PauseOptions pauses;
  uint64_t seed = motifmine::defaults::kSeed;
  int threads = 0;  // 0: all cores
  // The archive the trellis was built from: when set, instances that are held poses
  // (held_pose.h, at the trellis's eps) are kept out of the motifs.
  const FrameFileReader* archive = nullptr;
  // (stage, done, total): stage "similarity" counts instance columns read.
  std::function<void(const std::string&, uint64_t, uint64_t)> progress;
};

struct Motif {
  std::vector<uint32_t> instances;  // ids into ClusterResult::instances, ascending (= by start)
  uint64_t total_frames = 0;        // instance count × mean length
  // With the archive set: the medoid (an index into `instances`) and each instance's warped
  // distance to it (motif_representatives.h); `distances` empty without the archive.
  uint32_t representative = 0;
  std::vector<double> distances = {};
  // The ranking: (instance count - 1) × mean length, the frames the motif explains beyond its
  // first instance. A movement repeated often and at length comes first; among the scales of
  // one repeated movement (one repetition a instance, or two, ...) the finest.
  double score() const {
    return instances.empty()
               ? 0.0
               : static_cast<double>(total_frames) * static_cast<double>(instances.size() - 1) /
                     static_cast<double>(instances.size());
  }
  double mean_length() const {
    return instances.empty()
               ? 0.0
               : static_cast<double>(total_frames) / static_cast<double>(instances.size());
  }
};

struct ClusterReport {
  InstanceSetStats instance_stats;
  SimilarityStats similarity_stats;
  NormalizedCutStats cut_stats;
  uint64_t clustered_instances = 0;  // in a kept motif
  uint64_t length_outliers = 0;      // fragments dropped by the split by length
  uint64_t held_poses = 0;           // instances kept out as held poses
  uint64_t pauses = 0;               // still stretches of the archive (pauses.h)
  WarpedSimilarityStats warped_stats;
  uint64_t covered_frames = 0;  // distinct frames inside some motif instance
  double instance_seconds = 0;
  double sample_seconds = 0;  // the instances' samples and held poses read (instance_samples.h)
  double cut_seconds = 0;
  double representative_seconds = 0;  // motif_representatives.h
};

struct ClusterResult {
  std::vector<MotifInstance> instances;  // every merged instance, by start
  std::vector<InstanceLink> links;
  std::vector<Motif> motifs;  // most important first
  ClusterReport report;
};

// InvalidArgument if a candidate lies outside the trellis; Corruption from the trellis.
Result<ClusterResult> ClusterMotifs(const std::vector<PathCandidate>& candidates,
                                    const TrellisFileReader& trellis,
                                    const ClusterOptions& options);

// Groups of instance ids -> motifs ranked as above, each group split by length (exposed for
// tests; max_length_ratio 0 keeps the groups). `links` are the path links between instances;
// `length_outliers`, when given, receives the number of fragments dropped.
std::vector<Motif> RankMotifs(const std::vector<std::vector<uint32_t>>& groups,
                              const std::vector<MotifInstance>& instances,
                              const std::vector<InstanceLink>& links = {},
                              double max_length_ratio = 0.0, uint64_t* length_outliers = nullptr);

}  // namespace motif
