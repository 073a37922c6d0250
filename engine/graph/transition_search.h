// Transitions of a motion graph (Kovar, Gleicher & Pighin 2002, "Motion Graphs") found in the
// matching trellis instead of by an O(N^2) pass: a transition from frame s to frame g means
// that the windows [s, s + L) and [g, g + L) (L = window_frames, each inside its clip, and g's
// clip going on after g + L) look alike, so a walk can blend from the first into the second over
// those L frames and go on after g + L.
//  * candidates: every trellis entry (s, g) (D(s, g) <= eps) whose window pairs (s + o, g + o)
//    are trellis entries too, for o = step, 2 step, ... and L - 1: every checked pair of the
//    window within eps. Its cost is the mean distance of the checked pairs. Pairs in one clip
//    less than L frames apart are left out (a window over itself);
//  * transitions: the candidates that are local minima of the cost in (s, g), within L / 2
//    frames on both axes (ties: the lower (s, g) wins), so one good alignment gives one
//    transition, not the dozens of shifted pairs around it.
// Columns are read a chunk at a time (kColumnsPerTask plus L), searched in parallel and put
// back in order: the result does not depend on the thread count. Memory: the chunks in flight
// and the local minima of each column along g (a few per column); each chunk's pages of the
// mapped trellis are given back to the kernel when it is done.
// Thread-safety: a pure function; it runs in its own task_arena.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "common/status.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {

struct TransitionOptions {
  uint32_t window_frames = 30;                       // L: the blend window (0.25 s at 120 fps)
  uint32_t check_step = 5;                           // frames between the window's checked pairs
  int threads = 0;                                   // 0: all cores
  std::function<void(uint64_t, uint64_t)> progress;  // (columns done, columns)
};

struct Transition {
  uint64_t source = 0;  // archive frame: the walk leaves over [source, source + L)
  uint64_t target = 0;  // archive frame: it arrives over [target, target + L)
  float cost = 0;       // mean pose distance over the checked pairs of the window
};

struct TransitionSearch {
  std::vector<Transition> transitions;  // ordered by (source, target)
  uint64_t candidates = 0;              // window pairs within eps, before the local minima
};

// The first frame of each clip and one past the last, as the archive stores them.
struct ClipBounds {
  std::vector<uint64_t> starts;  // increasing; starts.size() = clips + 1, the last is N
  // The clip holding archive frame `frame` (< N).
  uint32_t ClipOf(uint64_t frame) const;
};
ClipBounds ClipBoundsOf(const FrameFileReader& reader);

// InvalidArgument: window_frames < 2, check_step 0, a trellis of another frame count; errors of
// the trellis reader pass through.
Result<TransitionSearch> FindTransitions(const TrellisFileReader& trellis, const ClipBounds& clips,
                                         const TransitionOptions& options);

}  // namespace motif
