#include "engine/cluster/instance_rows.h"

#include <algorithm>
#include <numeric>
#include <string>

namespace motif {

Status ForEachInstanceRows(const FrameFileReader& archive,
                           const std::vector<MotifInstance>& instances,
                           const std::function<Status(size_t, const float*)>& visit) {
  for (const MotifInstance& instance : instances) {
    if (instance.end > archive.frame_count() || instance.end <= instance.start) {
      return Status::InvalidArgument("instance [" + std::to_string(instance.start) + ", " +
                                     std::to_string(instance.end) +
                                     ") is not a frame range of the archive");
    }
  }
  std::vector<size_t> order(instances.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return instances[a].start < instances[b].start; });
  const uint64_t stride = archive.layout().stride();
  std::vector<float> rows;
  for (size_t first = 0; first < order.size();) {
    // The span [start, end) of instances order[first, last).
    const uint64_t start = instances[order[first]].start;
    uint64_t end = instances[order[first]].end;
    size_t last = first + 1;
    while (last < order.size()) {
      const MotifInstance& next = instances[order[last]];
      const uint64_t joined_end = std::max(end, next.end);
      if (next.start > end + kJoinGapFrames || joined_end - start > kMaxSpanFrames) break;
      end = joined_end;
      ++last;
    }
    MOTIF_RETURN_IF_ERROR(archive.ReadFrames(start, end - start, &rows));
    for (size_t at = first; at < last; ++at) {
      const size_t idx = order[at];
      MOTIF_RETURN_IF_ERROR(visit(idx, rows.data() + (instances[idx].start - start) * stride));
    }
    first = last;
  }
  return Status::Ok();
}

}  // namespace motif
