// Stick figures of poses, for the HTML report (report_html.h): a pose's points (from
// forward_kinematics.h) are projected orthographically into a small box (about 80x120 px) and
// drawn as one SVG path in which every bone is one straight segment between a parent point and a
// child point. Bones are grouped into chains (root to a leaf, then the side branches) so a point
// shared by consecutive bones is written once.
//
// Projection: the instance's heading (the root's rotation about the vertical axis) is removed,
// so every instance of a motif faces the same way; the side view puts the rest frame's Z axis
// (the direction a CMU skeleton faces) to the right, the front view its X axis; Y is up.
// Coordinates are rounded to 0.1 px and clamped to [kFigureCoordMin, kFigureCoordMax], so the
// SVG text and the compact encoding (EncodeFigurePoints) draw exactly the same figure.
// Thread-safety: pure functions and value types.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "formats/motion/skeleton.h"

namespace motif {

enum class FigureView : uint8_t {
  kSide = 0,   // horizontal axis: rest-frame Z
  kFront = 1,  // horizontal axis: rest-frame X
};

// Projected coordinates stay in this range (px), wide enough for any limb that leaves the box.
inline constexpr double kFigureCoordMin = -100.0;
inline constexpr double kFigureCoordMax = 309.5;  // kFigureCoordMin + 4095 / 10

// How a skeleton is drawn. `points` are the forward_kinematics.h points drawn (ascending);
// `chains` index into `points`, and consecutive entries of a chain are one bone.
struct StickFigureLayout {
  std::vector<uint32_t> points;
  std::vector<std::vector<uint32_t>> chains;

  size_t bone_count() const;
};

// The bones of `skeleton`: joint to child joint, joint to its end site. A bone shorter than
// `min_bone_fraction` of the rest pose's size (zero-length hip joints; hand, finger and thumb
// bones, under 3 px in an 80x120 figure) is not drawn: its child is drawn at its parent's point,
// so a figure has fewer points to store and looks the same. A one-joint skeleton has no bones.
// The largest extent of the skeleton's rest pose along an axis: its size (not just its height,
// so a skeleton whose rest pose lies along another axis still gets a sensible scale).
double RestPoseExtent(const Skeleton& skeleton);

StickFigureLayout MakeStickFigureLayout(const Skeleton& skeleton, double min_bone_fraction = 0.035);

using FigurePoint = std::array<double, 2>;  // x right, y down, px

struct FigureProjection {
  FigureView view = FigureView::kSide;
  double width_px = 80;
  double height_px = 120;
  double margin_px = 6;
  double pixels_per_unit = 1;       // FigureScaleFor()
  double heading_rad = 0;           // removed (rotation about Y around `origin`)
  Eigen::Vector3d origin{0, 0, 0};  // (x, z): drawn at the box's centre; y: the floor, drawn at
                                    // the bottom margin
};

// The scale at which the skeleton's rest pose fills 90 % of the box's height inside its margins.
double FigureScaleFor(const Skeleton& skeleton, double height_px, double margin_px);

// Projects, rounds and clamps `points` (world positions).
std::vector<FigurePoint> ProjectPose(const std::vector<Eigen::Vector3d>& points,
                                     const FigureProjection& projection);

// The drawn points of a pose: ProjectPose of `pose_points[layout.points[i]]`. `pose_points` are
// all the forward_kinematics.h points of the pose.
std::vector<FigurePoint> ProjectFigure(const StickFigureLayout& layout,
                                       const std::vector<Eigen::Vector3d>& pose_points,
                                       const FigureProjection& projection);

// `<svg class="fig" width=W height=H viewBox="0 0 W H"><path d="M..L.."/></svg>`: one 'L' per
// bone. The stroke style comes from the page's CSS (class "fig"). Precondition: figure_points
// has layout.points.size() entries (ProjectFigure).
std::string StickFigureSvg(const StickFigureLayout& layout,
                           const std::vector<FigurePoint>& figure_points, double width_px,
                           double height_px);

// Compact text of projected points for figures drawn later by the report's script: per point x
// then y, each as (value - kFigureCoordMin) * 10 in two base64url characters (A-Z a-z 0-9 - _,
// high digit first). Nothing in it needs escaping in HTML or JSON.
std::string EncodeFigurePoints(const std::vector<FigurePoint>& points);

// A coordinate as SVG writes it: at most one decimal, no trailing ".0" ("12", "-3.5").
std::string FormatFigureCoord(double value);

}  // namespace motif
