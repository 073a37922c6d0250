#include "engine/ingest/duplicate_takes.h"

#include <algorithm>
#include <cmath>

namespace motif {

DuplicateTakes::DuplicateTakes(const FrameFileReader* stored, FrameLayout layout)
    : stored_(stored), layout_(layout) {
  if (stored_ == nullptr) return;
  for (const ClipInfo& info : stored_->clips()) by_frames_.emplace(info.frame_count, Known{info, {}});
}

// The joints' quaternions of kSamples evenly spaced frames (first and last included).
std::vector<float> DuplicateTakes::Samples(const float* rows, uint64_t frame_count) const {
  const size_t quaternions = 4 * static_cast<size_t>(layout_.joint_count);
  std::vector<float> samples;
  samples.reserve(kSamples * quaternions);
  for (uint32_t sample = 0; sample < kSamples; ++sample) {
    const uint64_t frame = frame_count <= 1 ? 0 : sample * (frame_count - 1) / (kSamples - 1);
    const float* row = rows + frame * layout_.stride();
    samples.insert(samples.end(), row, row + quaternions);
  }
  return samples;
}

Status DuplicateTakes::ReadSamples(Known* known) const {
  std::vector<float> rows;
  std::vector<float> row;
  const uint64_t count = known->info.frame_count;
  for (uint32_t sample = 0; sample < kSamples; ++sample) {
    const uint64_t frame = count <= 1 ? 0 : sample * (count - 1) / (kSamples - 1);
    MOTIF_RETURN_IF_ERROR(stored_->ReadFrames(known->info.first_frame + frame, 1, &row));
    rows.insert(rows.end(), row.begin(), row.end());
  }
  known->samples = Samples(rows.data(), kSamples);  // each of the kSamples rows once
  return Status::Ok();
}

bool DuplicateTakes::Same(const std::vector<float>& a, const std::vector<float>& b) const {
  if (a.size() != b.size()) return false;
  for (size_t q = 0; q + 4 <= a.size(); q += 4) {
    float minus = 0;
    float plus = 0;
    for (size_t c = q; c < q + 4; ++c) {
      minus = std::max(minus, std::fabs(a[c] - b[c]));
      plus = std::max(plus, std::fabs(a[c] + b[c]));
    }
    if (std::min(minus, plus) > kCopyTolerance) return false;
  }
  return true;
}

Result<std::optional<ClipInfo>> DuplicateTakes::FindCopy(const ClipFrames& clip) {
  const uint64_t count = clip.info.frame_count;
  if (count == 0 || clip.rows.size() < count * layout_.stride()) return std::optional<ClipInfo>();
  const std::vector<float> samples = Samples(clip.rows.data(), count);
  auto [first, last] = by_frames_.equal_range(count);
  for (auto it = first; it != last; ++it) {
    if (it->second.samples.empty()) MOTIF_RETURN_IF_ERROR(ReadSamples(&it->second));
    if (Same(samples, it->second.samples)) return std::optional<ClipInfo>(it->second.info);
  }
  return std::optional<ClipInfo>();
}

void DuplicateTakes::Add(const ClipFrames& clip) {
  const uint64_t count = clip.info.frame_count;
  if (count == 0 || clip.rows.size() < count * layout_.stride()) return;
  by_frames_.emplace(count, Known{clip.info, Samples(clip.rows.data(), count)});
}

}  // namespace motif
