// Reading the frames of many instances from the archive without decoding a block once per
// instance. Instances overlap and crowd together (a motif's near-copies, the pieces of one
// periodic path); reading each alone decoded the same blocks again and again (at 10^6 frames
// that doubled the cluster stage). The instances, taken by start, are joined into spans while the
// next one starts within kJoinGapFrames of the span's end and the span stays below
// kMaxSpanFrames; each span is decoded once.
// Thread-safety: pure function; the reader may be shared.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "common/status.h"
#include "engine/cluster/motif_instance.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

inline constexpr uint64_t kJoinGapFrames = 2048;
inline constexpr uint64_t kMaxSpanFrames = 16384;

// Calls visit(instance index, its rows: length() * layout().stride() floats) once per instance.
// With threads 1, in order of start (ties by index); otherwise the spans are decoded in parallel
// (threads 0: all cores) and `visit` runs concurrently for instances of different spans.
// InvalidArgument naming the instance if one lies outside the archive or is empty; errors of the
// reader and of `visit` pass through (the first in span order).
Status ForEachInstanceRows(const FrameFileReader& archive,
                           const std::vector<MotifInstance>& instances,
                           const std::function<Status(size_t, const float*)>& visit,
                           int threads = 1);

}  // namespace motif
