#include "engine/report/keyframe_figures.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/report/forward_kinematics.h"
#include "formats/motion/quaternion_math.h"

namespace motif {

KeyframeFigures::KeyframeFigures(const FrameFileReader& reader, FigureView view, uint32_t keyframes)
    : reader_(reader),
      keyframes_(std::max<uint32_t>(1, keyframes)),
      layout_(MakeStickFigureLayout(reader.skeleton())),
      stride_(reader.layout().stride()),
      cache_(reader) {
  projection_.view = view;
  projection_.pixels_per_unit =
      FigureScaleFor(reader.skeleton(), projection_.height_px, projection_.margin_px);
}

Result<std::vector<std::vector<FigurePoint>>> KeyframeFigures::Project(const ClipInfo& clip,
                                                                       uint64_t start,
                                                                       uint64_t end) {
  return ProjectFrames(clip, KeyframeFrames(start, end));
}

Result<std::vector<std::vector<FigurePoint>>> KeyframeFigures::ProjectFrames(
    const ClipInfo& clip, const std::vector<uint64_t>& frames) {
  const uint64_t global_start = clip.first_frame + frames.front();
  MOTIF_ASSIGN_OR_RETURN(const float* cached,
                         cache_.Rows(global_start, clip.first_frame + frames.back() + 1));
  std::vector<float> rows(frames.size() * stride_);
  for (size_t key_idx = 0; key_idx < frames.size(); ++key_idx) {
    const float* row = cached + (frames[key_idx] - frames.front()) * stride_;
    std::copy(row, row + stride_, rows.begin() + key_idx * stride_);
  }
  // The keyframes are not consecutive, so the root's integrated horizontal path is
  // meaningless; each figure is centred on its own root below, which cancels it. Height,
  // heading and joint rotations come straight from each row.
  const Take take = ClipFramesToTake(reader_.skeleton(), clip, rows.data(), frames.size());
  std::vector<size_t> all(frames.size());
  for (size_t key_idx = 0; key_idx < frames.size(); ++key_idx) all[key_idx] = key_idx;
  return ProjectTakeFrames(take, all);
}

Result<std::vector<float>> KeyframeFigures::SampleRows(const ClipInfo& clip, uint64_t start,
                                                       uint64_t end, uint32_t step) {
  MOTIF_ASSIGN_OR_RETURN(const float* cached,
                         cache_.Rows(clip.first_frame + start, clip.first_frame + end));
  std::vector<float> rows;
  rows.reserve(((end - start - 1) / step + 1) * stride_);
  for (uint64_t offset = 0; offset < end - start; offset += step) {
    rows.insert(rows.end(), cached + offset * stride_, cached + (offset + 1) * stride_);
  }
  return rows;
}

std::vector<std::vector<FigurePoint>> KeyframeFigures::ProjectTakeFrames(
    const Take& take, const std::vector<size_t>& frames) const {
  std::vector<std::vector<Eigen::Vector3d>> positions(frames.size());
  double floor = std::numeric_limits<double>::max();
  for (size_t key_idx = 0; key_idx < frames.size(); ++key_idx) {
    positions[key_idx] = TakeFramePositions(take, frames[key_idx]);
    for (const Eigen::Vector3d& point : positions[key_idx]) floor = std::min(floor, point.y());
  }
  FigureProjection projection = projection_;
  projection.heading_rad = HeadingOf(take.rotation(frames.front(), 0));
  std::vector<std::vector<FigurePoint>> projected(frames.size());
  for (size_t key_idx = 0; key_idx < frames.size(); ++key_idx) {
    const Eigen::Vector3d& root = take.root_positions[frames[key_idx]];
    projection.origin = Eigen::Vector3d(root.x(), floor, root.z());
    projected[key_idx] = ProjectFigure(layout_, positions[key_idx], projection);
  }
  return projected;
}

std::vector<uint64_t> KeyframeFigures::KeyframeFrames(uint64_t start, uint64_t end) const {
  std::vector<uint64_t> frames;
  const uint64_t length = end - start;
  for (uint32_t key_idx = 0; key_idx < keyframes_; ++key_idx) {
    frames.push_back(start + (keyframes_ == 1
                                  ? 0
                                  : static_cast<uint64_t>(std::llround(
                                        static_cast<double>(key_idx) *
                                        static_cast<double>(length - 1) / (keyframes_ - 1)))));
  }
  return frames;
}

std::string KeyframeFigures::TakeSvg(const Take& take) const {
  std::vector<size_t> frames;
  for (uint64_t frame : KeyframeFrames(0, take.frame_count())) frames.push_back(frame);
  std::string svg;
  for (const std::vector<FigurePoint>& points : ProjectTakeFrames(take, frames)) {
    svg += StickFigureSvg(layout_, points, projection_.width_px, projection_.height_px);
  }
  return svg;
}

Result<std::string> KeyframeFigures::Svg(const ClipInfo& clip, uint64_t start, uint64_t end) {
  MOTIF_ASSIGN_OR_RETURN(std::vector<std::vector<FigurePoint>> keyframes,
                         Project(clip, start, end));
  std::string svg;
  for (const std::vector<FigurePoint>& points : keyframes) {
    svg += StickFigureSvg(layout_, points, projection_.width_px, projection_.height_px);
  }
  return svg;
}

}  // namespace motif
