#include "engine/graph/motion_graph.h"

#include <algorithm>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/strong_components.hpp>

#include "common/split_mix64.h"

namespace motif {
namespace {

using NodeGraph = boost::adjacency_list<boost::vecS, boost::vecS, boost::directedS>;

// Node k's continuation in its clip: k + 1 when it is in the same clip, else UINT32_MAX.
uint32_t NextInClip(const MotionGraph& graph, const ClipBounds& clips, uint32_t node) {
  if (node + 1 >= graph.nodes.size()) return UINT32_MAX;
  const uint32_t clip = clips.ClipOf(graph.nodes[node]);
  return graph.nodes[node + 1] < clips.starts[clip + 1] ? node + 1 : UINT32_MAX;
}

std::vector<uint64_t> NodeFrames(const ClipBounds& clips,
                                 const std::vector<GraphTransition>& transitions,
                                 uint32_t window_frames) {
  std::vector<uint64_t> frames(clips.starts.begin(), clips.starts.end() - 1);
  for (const GraphTransition& t : transitions) {
    if (t.fate != TransitionFate::kKept) continue;
    frames.push_back(t.transition.source);
    frames.push_back(t.transition.target + window_frames);
  }
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  return frames;
}

// The strongly connected components of more than one node, numbered by size.
void FindComponents(const ClipBounds& clips, MotionGraph* graph) {
  const size_t n = graph->nodes.size();
  NodeGraph g(n);
  for (uint32_t node = 0; node < n; ++node) {
    const uint32_t next = NextInClip(*graph, clips, node);
    if (next != UINT32_MAX) boost::add_edge(node, next, g);
    for (uint32_t t : graph->leaving[node]) {
      boost::add_edge(
          node, graph->NodeAt(graph->transitions[t].transition.target + graph->window_frames), g);
    }
  }
  std::vector<int> raw(n, 0);
  const int count = n ? boost::strong_components(g, raw.data()) : 0;
  std::vector<uint64_t> size(static_cast<size_t>(count), 0);
  std::vector<uint32_t> first(static_cast<size_t>(count), UINT32_MAX);
  for (uint32_t node = 0; node < n; ++node) {
    const auto c = static_cast<size_t>(raw[node]);
    ++size[c];
    first[c] = std::min(first[c], node);
  }
  std::vector<size_t> order;
  for (size_t c = 0; c < size.size(); ++c) {
    if (size[c] > 1) order.push_back(c);
  }
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return size[a] > size[b] || (size[a] == size[b] && first[a] < first[b]);
  });
  std::vector<int32_t> number(size.size(), -1);
  for (size_t rank = 0; rank < order.size(); ++rank) {
    number[order[rank]] = static_cast<int32_t>(rank);
    graph->component_sizes.push_back(size[order[rank]]);
  }
  graph->component.resize(n);
  for (uint32_t node = 0; node < n; ++node) graph->component[node] = number[raw[node]];
}

}  // namespace

const char* TransitionFateName(TransitionFate fate) {
  switch (fate) {
    case TransitionFate::kKept:
      return "kept";
    case TransitionFate::kSignature:
      return "signature";
    case TransitionFate::kComponent:
      return "component";
  }
  return "?";
}

FateCounts CountFates(const std::vector<GraphTransition>& transitions) {
  FateCounts counts;
  for (const GraphTransition& edge : transitions) {
    counts.kept += edge.fate == TransitionFate::kKept;
    counts.signature += edge.fate == TransitionFate::kSignature;
    counts.component += edge.fate == TransitionFate::kComponent;
  }
  return counts;
}

uint32_t MotionGraph::NodeAt(uint64_t frame) const {
  const auto found = std::lower_bound(nodes.begin(), nodes.end(), frame);
  return found != nodes.end() && *found == frame ? static_cast<uint32_t>(found - nodes.begin())
                                                 : UINT32_MAX;
}

MotionGraph BuildMotionGraph(const ClipBounds& clips, std::vector<GraphTransition> transitions,
                             uint32_t window_frames) {
  MotionGraph graph;
  graph.window_frames = window_frames;
  graph.nodes = NodeFrames(clips, transitions, window_frames);
  graph.transitions = std::move(transitions);
  graph.leaving.assign(graph.nodes.size(), {});
  for (uint32_t t = 0; t < graph.transitions.size(); ++t) {
    if (graph.transitions[t].fate != TransitionFate::kKept) continue;
    graph.leaving[graph.NodeAt(graph.transitions[t].transition.source)].push_back(t);
  }
  FindComponents(clips, &graph);
  for (uint32_t node = 0; node < graph.nodes.size(); ++node) {
    std::vector<uint32_t>& leaving = graph.leaving[node];
    std::erase_if(leaving, [&](uint32_t t) {
      GraphTransition& edge = graph.transitions[t];
      const uint32_t arrival = graph.NodeAt(edge.transition.target + window_frames);
      const int32_t component = graph.component[node];
      if (component >= 0 && graph.component[arrival] == component) return false;
      edge.fate = TransitionFate::kComponent;
      return true;
    });
  }
  return graph;
}

uint64_t WalkFrames(const std::vector<WalkPiece>& pieces, uint32_t window_frames) {
  uint64_t frames = 0;
  for (const WalkPiece& piece : pieces) frames += piece.end - piece.start;
  return pieces.empty() ? 0 : frames - window_frames * (pieces.size() - 1);
}

Result<std::vector<WalkPiece>> RandomWalk(const MotionGraph& graph, const ClipBounds& clips,
                                          uint32_t start_clip, const WalkOptions& options) {
  const uint64_t frames = options.frames;
  if (frames == 0) return Status::InvalidArgument("walk: at least one frame");
  // The first node of the clip's largest component (components are numbered by size).
  uint32_t node = UINT32_MAX;
  for (uint32_t at = static_cast<uint32_t>(
           std::lower_bound(graph.nodes.begin(), graph.nodes.end(), clips.starts[start_clip]) -
           graph.nodes.begin());
       at < graph.nodes.size() && graph.nodes[at] < clips.starts[start_clip + 1]; ++at) {
    const int32_t c = graph.component[at];
    if (c >= 0 && (node == UINT32_MAX || c < graph.component[node])) node = at;
  }
  if (node == UINT32_MAX) {
    return Status::InvalidArgument(
        "walk: no frame of the clip is in a strongly connected "
        "component of the graph (no transition leads into it and "
        "back out)");
  }
  const uint32_t window = graph.window_frames;
  SplitMix64 random(options.seed);
  std::vector<WalkPiece> pieces;
  uint64_t piece_start = graph.nodes[node];  // archive frames until the piece is closed
  uint64_t played = 0;                       // frames of the closed pieces, less their junctions
  auto close = [&](uint64_t end) {
    const uint32_t clip = clips.ClipOf(piece_start);
    pieces.push_back({clip, piece_start - clips.starts[clip], end - clips.starts[clip]});
    played += end - piece_start - (pieces.size() > 1 ? window : 0);
  };
  // Every step plays frames but for a transition taken as soon as a piece starts; a walk that only
  // did that would never end.
  for (uint64_t steps = 0;; ++steps) {
    if (steps > 64 * frames + 1024)
      return Status::InvalidArgument("walk: no progress (transitions that play no frame)");
    const uint64_t here = graph.nodes[node];
    const uint64_t open = here - piece_start - (pieces.empty() ? 0 : window);
    if (played + open >= frames) {
      close(here - (played + open - frames));
      break;
    }
    const uint32_t next = NextInClip(graph, clips, node);
    const bool can_continue = next != UINT32_MAX && graph.component[next] == graph.component[node];
    // Before min_piece_frames the walk continues when it can.
    const bool settled = pieces.empty() || open >= options.min_piece_frames || !can_continue;
    const size_t choices = (settled ? graph.leaving[node].size() : 0) + (can_continue ? 1 : 0);
    if (choices == 0) {
      close(here);  // cannot happen inside a strongly connected component
      break;
    }
    const size_t pick = random.Next() % choices;
    if (can_continue && pick == choices - 1) {
      node = next;
      continue;
    }
    const Transition& t = graph.transitions[graph.leaving[node][pick]].transition;
    if (played + open + window >= frames) {  // the walk ends within the blend: no transition
      close(here + (frames - played - open));
      break;
    }
    close(t.source + window);
    piece_start = t.target;
    node = graph.NodeAt(t.target + window);
  }
  return pieces;
}

}  // namespace motif
