// Stick figures of poses, for the HTML report (report_html.h): a pose's points (from
// forward_kinematics.h) are projected orthographically into a box (kFigureWidthPx x
// kFigureHeightPx) and drawn as SVG paths in which every bone is one straight segment between a
// parent point and a child point. Bones are grouped into chains (root to a leaf, then the side
// branches) so a point shared by consecutive bones is written once. A bone is stroked in the colour
// of its child point's side (limb_side.h: left blue, right red, centre grey), as the player draws
// it: one path per side.
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
// `chains` index into `points`, and consecutive entries of a chain are one bone. `sides[i]` is
// the side of point i (JointSide of its joint's name; an end site takes its joint's); empty:
// every point centre.
struct StickFigureLayout {
  std::vector<uint32_t> points;
  std::vector<std::vector<uint32_t>> chains;
  std::vector<uint8_t> sides;

  size_t bone_count() const;
};

// The bones of `skeleton`: joint to child joint, joint to its end site. A bone shorter than
// `min_bone_fraction` of the rest pose's size (zero-length hip joints; hand, finger and thumb
// bones, under 5 px in a 168 px tall figure) is not drawn: its child is drawn at its parent's
// point, so a figure has fewer points to store and looks the same. A one-joint skeleton has no
// bones. The largest extent of the skeleton's rest pose along an axis: its size (not just its
// height, so a skeleton whose rest pose lies along another axis still gets a sensible scale).
double RestPoseExtent(const Skeleton& skeleton);

StickFigureLayout MakeStickFigureLayout(const Skeleton& skeleton, double min_bone_fraction = 0.035);

// The bones of one side: runs of points, consecutive entries of a run one bone, each bone's child
// point of `side`. Runs follow the chains, so a side's bones that meet are one run.
struct FigureStroke {
  uint8_t side = 0;
  std::vector<std::vector<uint32_t>> runs;
};

// The layout's bones by side, the sides that have bones in side order (centre, left, right):
// what StickFigureSvg strokes, one path each, and what a page's script strokes the same way.
std::vector<FigureStroke> FigureStrokes(const StickFigureLayout& layout);

using FigurePoint = std::array<double, 2>;  // x right, y down, px

// The keyframe figures' box: big enough that a limb's side and bend read at a glance.
inline constexpr double kFigureWidthPx = 112;
inline constexpr double kFigureHeightPx = 168;

struct FigureProjection {
  FigureView view = FigureView::kSide;
  double width_px = kFigureWidthPx;
  double height_px = kFigureHeightPx;
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

// `<svg class="fig" width=W height=H viewBox="0 0 W H"><path stroke="C" d="M..L.."/>...</svg>`:
// a path per FigureStrokes entry, C its side's LimbSideColour, one 'L' per bone. The stroke's
// width and caps come from the page's CSS (class "fig"). Precondition: figure_points has
// layout.points.size() entries (ProjectFigure).
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
