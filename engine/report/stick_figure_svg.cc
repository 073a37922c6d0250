#include "engine/report/stick_figure_svg.h"

#include <algorithm>
#include <cmath>

#include "engine/report/forward_kinematics.h"
#include "engine/report/limb_side.h"
#include "formats/motion/quaternion_math.h"

namespace motif {

namespace {

constexpr char kBase64Url[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";

// Tenths of a pixel: projected coordinates are stored exactly as these integers.
long ToTenths(double value) {
  const double clamped = std::clamp(value, kFigureCoordMin, kFigureCoordMax);
  return std::lround(clamped * 10.0);
}

}  // namespace

size_t StickFigureLayout::bone_count() const {
  size_t count = 0;
  for (const std::vector<uint32_t>& chain : chains) count += chain.size() - 1;
  return count;
}

double RestPoseExtent(const Skeleton& skeleton) {
  const std::vector<Eigen::Vector3d> rest = RestPosePositions(skeleton);
  if (rest.empty()) return 0;
  Eigen::Vector3d low = rest[0];
  Eigen::Vector3d high = rest[0];
  for (const Eigen::Vector3d& point : rest) {
    low = low.cwiseMin(point);
    high = high.cwiseMax(point);
  }
  return (high - low).maxCoeff();
}

namespace {

double Length(const std::array<double, 3>& offset) {
  return std::sqrt(offset[0] * offset[0] + offset[1] * offset[1] + offset[2] * offset[2]);
}

// JointSide of each of `points` (forward_kinematics.h numbering: the joints, then one end site
// per joint that has one, in joint order; an end site is on its joint's side).
std::vector<uint8_t> PointSides(const Skeleton& skeleton, const std::vector<uint32_t>& points) {
  std::vector<uint8_t> pose_sides;
  for (const Joint& joint : skeleton.joints()) pose_sides.push_back(JointSide(joint.name));
  for (const Joint& joint : skeleton.joints()) {
    if (joint.has_end_site) pose_sides.push_back(JointSide(joint.name));
  }
  std::vector<uint8_t> sides;
  for (uint32_t point : points) sides.push_back(pose_sides.at(point));
  return sides;
}

}  // namespace

StickFigureLayout MakeStickFigureLayout(const Skeleton& skeleton, double min_bone_fraction) {
  StickFigureLayout layout;
  const size_t joint_count = skeleton.joint_count();
  if (joint_count == 0) return layout;
  const double min_length = min_bone_fraction * RestPoseExtent(skeleton);
  // drawn_as[joint]: the point a joint is drawn at (itself, or the ancestor its short bones
  // collapse onto). children: the drawn bones, by their upper point.
  std::vector<uint32_t> drawn_as(joint_count, 0);
  std::vector<std::vector<uint32_t>> children(PosePointCount(skeleton));
  for (size_t joint_idx = 1; joint_idx < joint_count; ++joint_idx) {
    const Joint& joint = skeleton.joint(joint_idx);
    const uint32_t parent = drawn_as[joint.parent];
    if (Length(joint.offset) < min_length) {
      drawn_as[joint_idx] = parent;
    } else {
      drawn_as[joint_idx] = static_cast<uint32_t>(joint_idx);
      children[parent].push_back(static_cast<uint32_t>(joint_idx));
    }
  }
  uint32_t end_site_point = static_cast<uint32_t>(joint_count);
  for (size_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    const Joint& joint = skeleton.joint(joint_idx);
    if (!joint.has_end_site) continue;
    if (Length(joint.end_site) >= min_length)
      children[drawn_as[joint_idx]].push_back(end_site_point);
    ++end_site_point;
  }
  // Each chain follows first children down to a leaf; the other children of every point it
  // passes start chains of their own (from that point), so each bone is drawn exactly once.
  std::vector<std::vector<uint32_t>> chains;
  std::vector<std::pair<uint32_t, uint32_t>> pending;  // (from point, first child)
  for (auto it = children[0].rbegin(); it != children[0].rend(); ++it) pending.push_back({0, *it});
  while (!pending.empty()) {
    auto [from, point] = pending.back();
    pending.pop_back();
    std::vector<uint32_t> chain = {from, point};
    while (!children[point].empty()) {
      const std::vector<uint32_t>& kids = children[point];
      for (size_t kid_idx = kids.size() - 1; kid_idx > 0; --kid_idx) {
        pending.push_back({point, kids[kid_idx]});
      }
      point = kids[0];
      chain.push_back(point);
    }
    chains.push_back(std::move(chain));
  }
  // Renumber into the drawn points only.
  std::vector<int64_t> index_of(children.size(), -1);
  for (const std::vector<uint32_t>& chain : chains) {
    for (uint32_t point : chain) index_of[point] = 0;
  }
  for (size_t point = 0; point < index_of.size(); ++point) {
    if (index_of[point] < 0) continue;
    index_of[point] = static_cast<int64_t>(layout.points.size());
    layout.points.push_back(static_cast<uint32_t>(point));
  }
  for (std::vector<uint32_t>& chain : chains) {
    for (uint32_t& point : chain) point = static_cast<uint32_t>(index_of[point]);
  }
  layout.chains = std::move(chains);
  layout.sides = PointSides(skeleton, layout.points);
  return layout;
}

std::vector<FigureStroke> FigureStrokes(const StickFigureLayout& layout) {
  std::vector<FigureStroke> by_side(kLimbSideCount);
  for (int side = 0; side < kLimbSideCount; ++side) by_side[side].side = static_cast<uint8_t>(side);
  for (const std::vector<uint32_t>& chain : layout.chains) {
    int previous_side = -1;  // the side of the chain's previous bone: its run goes on
    for (size_t step = 1; step < chain.size(); ++step) {
      const int side = layout.sides.empty() ? 0 : std::min<int>(layout.sides[chain[step]], 2);
      std::vector<std::vector<uint32_t>>& runs = by_side[side].runs;
      if (side != previous_side) runs.push_back({chain[step - 1]});
      runs.back().push_back(chain[step]);
      previous_side = side;
    }
  }
  std::vector<FigureStroke> strokes;
  for (FigureStroke& stroke : by_side) {
    if (!stroke.runs.empty()) strokes.push_back(std::move(stroke));
  }
  return strokes;
}

double FigureScaleFor(const Skeleton& skeleton, double height_px, double margin_px) {
  const double extent = RestPoseExtent(skeleton);
  const double usable = std::max(1.0, height_px - 2 * margin_px);
  return extent > 1e-9 ? 0.9 * usable / extent : 1.0;
}

std::vector<FigurePoint> ProjectPose(const std::vector<Eigen::Vector3d>& points,
                                     const FigureProjection& projection) {
  const Eigen::Quaterniond unturn = AxisRotation(Axis::kY, -projection.heading_rad);
  std::vector<FigurePoint> projected;
  projected.reserve(points.size());
  for (const Eigen::Vector3d& point : points) {
    Eigen::Vector3d local = point - projection.origin;
    const double up = local.y();
    local.y() = 0;
    local = unturn * local;
    const double across = projection.view == FigureView::kSide ? local.z() : local.x();
    const double x = projection.width_px / 2 + projection.pixels_per_unit * across;
    const double y = projection.height_px - projection.margin_px - projection.pixels_per_unit * up;
    projected.push_back({ToTenths(x) / 10.0, ToTenths(y) / 10.0});
  }
  return projected;
}

std::vector<FigurePoint> ProjectFigure(const StickFigureLayout& layout,
                                       const std::vector<Eigen::Vector3d>& pose_points,
                                       const FigureProjection& projection) {
  std::vector<Eigen::Vector3d> drawn;
  drawn.reserve(layout.points.size());
  for (uint32_t point : layout.points) drawn.push_back(pose_points[point]);
  return ProjectPose(drawn, projection);
}

std::string FormatFigureCoord(double value) {
  const long tenths = ToTenths(value);
  std::string text = tenths < 0 ? "-" : "";
  const long magnitude = std::labs(tenths);
  text += std::to_string(magnitude / 10);
  if (magnitude % 10 != 0) {
    text += '.';
    text += static_cast<char>('0' + magnitude % 10);
  }
  return text;
}

std::string StickFigureSvg(const StickFigureLayout& layout,
                           const std::vector<FigurePoint>& figure_points, double width_px,
                           double height_px) {
  const std::string width = FormatFigureCoord(width_px);
  const std::string height = FormatFigureCoord(height_px);
  std::string svg = "<svg class=\"fig\" width=\"" + width + "\" height=\"" + height +
                    "\" viewBox=\"0 0 " + width + " " + height + "\">";
  for (const FigureStroke& stroke : FigureStrokes(layout)) {
    svg += std::string("<path stroke=\"") + LimbSideColour(stroke.side) + "\" d=\"";
    for (const std::vector<uint32_t>& run : stroke.runs) {
      for (size_t step = 0; step < run.size(); ++step) {
        const FigurePoint& point = figure_points[run[step]];
        svg += step == 0 ? 'M' : 'L';
        svg += FormatFigureCoord(point[0]);
        svg += ' ';
        svg += FormatFigureCoord(point[1]);
      }
    }
    svg += "\"/>";
  }
  svg += "</svg>";
  return svg;
}

std::string EncodeFigurePoints(const std::vector<FigurePoint>& points) {
  std::string text;
  text.reserve(points.size() * 4);
  const long min_tenths = std::lround(kFigureCoordMin * 10.0);
  for (const FigurePoint& point : points) {
    for (double value : point) {
      const long code = ToTenths(value) - min_tenths;  // 0..4095
      text += kBase64Url[code / 64];
      text += kBase64Url[code % 64];
    }
  }
  return text;
}

}  // namespace motif
