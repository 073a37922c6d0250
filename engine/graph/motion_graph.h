// A motion graph over an archive (Kovar, Gleicher & Pighin 2002): the takes, cut at the frames
// where transitions leave or arrive, joined by the transitions (transition_search.h), reduced
// to its largest strongly connected component so that a random walk never dead-ends.
//  * nodes: archive frames, sorted: each clip's first frame, each transition's source s (where
//    the walk starts to blend away) and arrival a = target + L (where it goes on unblended);
//  * edges: within a clip, from each node to the next node of the clip (play the frames between);
//    and each transition that is not pruned, from node s to node a (play [s, s + L) blended into
//    [target, target + L));
//  * the components: the strongly connected components, by Boost's strong_components (Tarjan).
//    Kovar et al. keep only the largest, so that a walk never dead-ends. With the signature
//    constraint the graph falls apart into islands of one style, and the largest need not hold
//    the clip a walk is to start in (on the CMU takes it is the walks'). So every component of
//    more than one node is kept, each closed: a transition between two components, or with an
//    end in a one-node component, is pruned ("component"). A walk never dead-ends in any of
//    them, and never leaves the one it starts in. Numbered by size (0: the largest; ties: the
//    one with the lower first node).
// A random walk starts at the first node of a clip in that clip's largest component and, at
// each node, takes one
// of its edges (the clip's continuation and the transitions leaving there) with equal chance
// (SplitMix64 from the seed), until it has played the frames asked for; after a transition it
// plays at least min_piece_frames before the next (WalkOptions).
// Thread-safety: value types and pure functions.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/graph/transition_search.h"

namespace motif {

enum class TransitionFate : uint8_t {
  kKept = 0,
  kSignature = 1,  // its signature distance is above the threshold (or a side has no words)
  kComponent = 2,  // an end lies outside the largest strongly connected component
};
const char* TransitionFateName(TransitionFate fate);  // "kept", "signature", "component"

struct GraphTransition {
  Transition transition;
  double signature_distance = std::numeric_limits<double>::quiet_NaN();  // NaN: not measured
  TransitionFate fate = TransitionFate::kKept;
};

struct MotionGraph {
  uint32_t window_frames = 0;
  std::vector<uint64_t> nodes;            // archive frames, increasing
  std::vector<int32_t> component;         // per node: its component, or -1 (one node alone)
  std::vector<uint64_t> component_sizes;  // nodes per component, largest first
  std::vector<GraphTransition> transitions;
  std::vector<std::vector<uint32_t>> leaving;  // per node: its kept transitions (indices)

  // The node at archive frame `frame`, or UINT32_MAX.
  uint32_t NodeAt(uint64_t frame) const;
};

// How many transitions met each fate.
struct FateCounts {
  uint64_t kept = 0;
  uint64_t signature = 0;
  uint64_t component = 0;
};
FateCounts CountFates(const std::vector<GraphTransition>& transitions);

// Builds the graph from `transitions` (those already pruned keep their fate and add no edge)
// and prunes it to its closed components.
MotionGraph BuildMotionGraph(const ClipBounds& clips, std::vector<GraphTransition> transitions,
                             uint32_t window_frames);

// A piece of a walk: frames [start, end) of clip `clip` (clip-relative). A piece after the first
// starts with the window_frames frames that are blended with the last window_frames frames of
// the piece before it.
struct WalkPiece {
  uint32_t clip = 0;
  uint64_t start = 0;
  uint64_t end = 0;
};

struct WalkOptions {
  uint64_t frames = 0;  // of output: the pieces' frames, less window_frames at each junction
  uint64_t seed = 1;
  // After arriving by a transition the walk plays at least this many frames (past the blend)
  // before it may take another: without it, a walk through a dense graph changes takes every
  // few frames.
  uint64_t min_piece_frames = 120;
};

// From the first node of `start_clip` in the largest component holding a node of it.
// InvalidArgument: no node of start_clip in a component, frames 0.
Result<std::vector<WalkPiece>> RandomWalk(const MotionGraph& graph, const ClipBounds& clips,
                                          uint32_t start_clip, const WalkOptions& options);

// The frames a walk plays: the sum of its pieces, less window_frames per junction.
uint64_t WalkFrames(const std::vector<WalkPiece>& pieces, uint32_t window_frames);

}  // namespace motif
