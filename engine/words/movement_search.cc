#include "engine/words/movement_search.h"

#include <algorithm>
#include <string>
#include <vector>

#include "engine/signature/take_movement.h"
#include "formats/motion/body_landmarks.h"

namespace motif {
namespace {

// The takes long enough to compare, the query among them (its place in *query_slot).
Result<std::vector<uint32_t>> ComparableClips(const FrameFileReader& reader, uint32_t query_clip,
                                              size_t* query_slot, SearchResult* result) {
  const std::vector<ClipInfo>& clips = reader.clips();
  const uint64_t minimum = MovementMinimumFrames(reader.fps());
  if (clips[query_clip].frame_count < minimum) {
    return Status::InvalidArgument("search: clip " + clips[query_clip].name +
                                   " is too short to compare by movement (" +
                                   std::to_string(clips[query_clip].frame_count) +
                                   " frames; it needs " + std::to_string(minimum) + ")");
  }
  std::vector<uint32_t> compared;
  for (uint32_t clip = 0; clip < clips.size(); ++clip) {
    if (clips[clip].frame_count < minimum) {
      result->wordless_clips.push_back(clip);
      continue;
    }
    if (clip == query_clip) *query_slot = compared.size();
    compared.push_back(clip);
  }
  return compared;
}

}  // namespace

Result<SearchResult> WholeTakeMovementSearch(const FrameFileReader& reader, uint32_t query_clip,
                                             uint32_t top, int threads) {
  if (query_clip >= reader.clips().size()) {
    return Status::InvalidArgument("search: no clip " + std::to_string(query_clip));
  }
  if (top == 0) return Status::InvalidOption("top", "must be at least 1");
  SearchResult result;
  result.distance = "movement";
  result.whole_take = true;
  size_t query_slot = 0;
  MOTIF_ASSIGN_OR_RETURN(std::vector<uint32_t> compared,
                         ComparableClips(reader, query_clip, &query_slot, &result));
  MOTIF_ASSIGN_OR_RETURN(BodyLandmarks landmarks, FindBodyLandmarks(reader.skeleton()));
  std::vector<TakeMovement> takes;
  for (uint32_t clip : compared) {
    MOTIF_ASSIGN_OR_RETURN(TakeMovement movement, ReadTakeMovement(reader, clip, landmarks));
    takes.push_back(std::move(movement));
  }
  const std::vector<double> distances = MovementDistancesFrom(takes, query_slot, threads);
  std::vector<size_t> order;
  for (size_t slot = 0; slot < compared.size(); ++slot) {
    if (slot != query_slot) order.push_back(slot);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return distances[a] < distances[b]; });
  for (size_t rank = 0; rank < order.size() && rank < top; ++rank) {
    const uint32_t clip = compared[order[rank]];
    WindowMatch match;
    match.clip = clip;
    match.end_frame = reader.clips()[clip].frame_count;
    match.distance = distances[order[rank]];
    match.whole_take = true;
    result.matches.push_back(match);
    result.profiles.push_back({static_cast<float>(match.distance)});
  }
  result.windows = order.size();
  return result;
}

}  // namespace motif
