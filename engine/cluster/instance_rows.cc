#include "engine/cluster/instance_rows.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <numeric>
#include <string>

namespace motif {

namespace {

// Instances order[first, last) read together as the frames [start, end).
struct Span {
  size_t first = 0;
  size_t last = 0;
  uint64_t start = 0;
  uint64_t end = 0;
};

// The instances by start, joined into spans (instance_rows.h).
std::vector<Span> JoinIntoSpans(const std::vector<MotifInstance>& instances,
                                std::vector<size_t>* order) {
  order->resize(instances.size());
  std::iota(order->begin(), order->end(), size_t{0});
  std::stable_sort(order->begin(), order->end(),
                   [&](size_t a, size_t b) { return instances[a].start < instances[b].start; });
  std::vector<Span> spans;
  for (size_t first = 0; first < order->size();) {
    Span span{first, first + 1, instances[(*order)[first]].start, instances[(*order)[first]].end};
    while (span.last < order->size()) {
      const MotifInstance& next = instances[(*order)[span.last]];
      const uint64_t joined_end = std::max(span.end, next.end);
      if (next.start > span.end + kJoinGapFrames || joined_end - span.start > kMaxSpanFrames) {
        break;
      }
      span.end = joined_end;
      ++span.last;
    }
    spans.push_back(span);
    first = span.last;
  }
  return spans;
}

}  // namespace

Status ForEachInstanceRows(const FrameFileReader& archive,
                           const std::vector<MotifInstance>& instances,
                           const std::function<Status(size_t, const float*)>& visit,
                           int threads) {
  for (const MotifInstance& instance : instances) {
    if (instance.end > archive.frame_count() || instance.end <= instance.start) {
      return Status::InvalidArgument("instance [" + std::to_string(instance.start) + ", " +
                                     std::to_string(instance.end) +
                                     ") is not a frame range of the archive");
    }
  }
  std::vector<size_t> order;
  const std::vector<Span> spans = JoinIntoSpans(instances, &order);
  const uint64_t stride = archive.layout().stride();
  auto read_span = [&](const Span& span, std::vector<float>* rows) -> Status {
    MOTIF_RETURN_IF_ERROR(archive.ReadFrames(span.start, span.end - span.start, rows));
    for (size_t at = span.first; at < span.last; ++at) {
      const size_t idx = order[at];
      MOTIF_RETURN_IF_ERROR(visit(idx, rows->data() + (instances[idx].start - span.start) * stride));
    }
    return Status::Ok();
  };
  if (threads == 1) {
    std::vector<float> rows;
    for (const Span& span : spans) MOTIF_RETURN_IF_ERROR(read_span(span, &rows));
    return Status::Ok();
  }
  std::vector<Status> statuses(spans.size());
  auto read_all = [&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, spans.size()), [&](const auto& range) {
      std::vector<float> rows;
      for (size_t idx = range.begin(); idx != range.end(); ++idx) {
        statuses[idx] = read_span(spans[idx], &rows);
      }
    });
  };
  if (threads > 0) {
    tbb::task_arena(threads).execute(read_all);
  } else {
    read_all();
  }
  for (const Status& status : statuses) MOTIF_RETURN_IF_ERROR(status);
  return Status::Ok();
}

}  // namespace motif
