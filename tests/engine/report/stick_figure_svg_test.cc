#include "engine/report/stick_figure_svg.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <set>

#include "engine/report/forward_kinematics.h"
#include "engine/report/limb_side.h"
#include "engine/synth/cmu_body_model.h"
#include "formats/motion/quaternion_math.h"

namespace motif {
namespace {

// root with two legs and a spine; the spine has a head end site; a lone arm branches off it.
Skeleton Branchy() {
  std::vector<Joint> joints(6);
  joints[0].name = "root";
  joints[1] = {"lleg", 0, {1, -1, 0}, true, {0, -1, 0}, {}, 0};
  joints[2] = {"rleg", 0, {-1, -1, 0}, true, {0, -1, 0}, {}, 0};
  joints[3] = {"spine", 0, {0, 1, 0}, false, {}, {}, 0};
  joints[4] = {"neck", 3, {0, 1, 0}, true, {0, 0.5, 0}, {}, 0};
  joints[5] = {"arm", 3, {1, 0.5, 0}, false, {}, {}, 0};
  return Skeleton("custom", joints);
}

size_t Count(const std::string& text, char c) { return std::count(text.begin(), text.end(), c); }

TEST(StickFigureLayout, DrawsEveryBoneOnce) {
  const Skeleton skeleton = Branchy();
  const StickFigureLayout layout = MakeStickFigureLayout(skeleton);
  EXPECT_EQ(layout.points.size(), 9u);  // 6 joints + 3 end sites, numbered as in FK
  // 5 joint-to-parent bones + 3 end sites.
  EXPECT_EQ(layout.bone_count(), 8u);
  std::set<std::pair<uint32_t, uint32_t>> bones;
  for (const std::vector<uint32_t>& chain : layout.chains) {
    ASSERT_GE(chain.size(), 2u);
    for (size_t step = 1; step < chain.size(); ++step) {
      EXPECT_TRUE(bones.insert({chain[step - 1], chain[step]}).second) << "bone drawn twice";
    }
  }
  const std::set<std::pair<uint32_t, uint32_t>> expected = {{0, 1}, {0, 2}, {0, 3}, {3, 4},
                                                            {3, 5}, {1, 6}, {2, 7}, {4, 8}};
  EXPECT_EQ(bones, expected);
}

TEST(StickFigureLayout, OneJointSkeletonHasNoBones) {
  std::vector<Joint> joints(1);
  joints[0].name = "root";
  EXPECT_EQ(MakeStickFigureLayout(Skeleton("custom", joints)).bone_count(), 0u);
}

TEST(StickFigureLayout, ShortBonesCollapseOntoTheirParent) {
  const Skeleton skeleton = CmuBodyModel::Get().skeleton();
  size_t end_sites = 0;
  for (const Joint& joint : skeleton.joints()) end_sites += joint.has_end_site ? 1 : 0;
  const StickFigureLayout all = MakeStickFigureLayout(skeleton, 0.0);
  EXPECT_EQ(all.bone_count(), skeleton.joint_count() - 1 + end_sites);
  EXPECT_EQ(all.points.size(), PosePointCount(skeleton));
  const StickFigureLayout drawn = MakeStickFigureLayout(skeleton);
  EXPECT_LT(drawn.points.size(), all.points.size());
  EXPECT_EQ(drawn.bone_count() + 1, drawn.points.size()) << "still a tree";
  EXPECT_GE(drawn.bone_count(), 14u) << "legs, spine, head and arms stay";
  // Every drawn bone is at least 3.5 % of the rest pose's size.
  const std::vector<Eigen::Vector3d> rest = RestPosePositions(skeleton);
  Eigen::Vector3d low = rest[0];
  Eigen::Vector3d high = rest[0];
  for (const Eigen::Vector3d& point : rest) {
    low = low.cwiseMin(point);
    high = high.cwiseMax(point);
  }
  const double extent = (high - low).maxCoeff();
  for (const std::vector<uint32_t>& chain : drawn.chains) {
    for (size_t step = 1; step < chain.size(); ++step) {
      const double length =
          (rest[drawn.points[chain[step]]] - rest[drawn.points[chain[step - 1]]]).norm();
      EXPECT_GE(length, 0.035 * extent);
    }
  }
}

TEST(StickFigureSvg, HasOneSegmentPerBoneAndOneDecimal) {
  const Skeleton skeleton = CmuBodyModel::Get().skeleton();
  const StickFigureLayout layout = MakeStickFigureLayout(skeleton);

  FigureProjection projection;
  projection.pixels_per_unit = FigureScaleFor(skeleton, projection.height_px, projection.margin_px);
  const std::vector<FigurePoint> points =
      ProjectFigure(layout, RestPosePositions(skeleton), projection);
  const std::string svg = StickFigureSvg(layout, points, 80, 120);
  EXPECT_EQ(svg.rfind("<svg class=\"fig\" width=\"80\" height=\"120\" viewBox=\"0 0 80 120\">", 0),
            0u)
      << svg;
  EXPECT_EQ(Count(svg, 'L'), layout.bone_count());  // one line segment per bone
  size_t runs = 0;
  for (const FigureStroke& stroke : FigureStrokes(layout)) runs += stroke.runs.size();
  EXPECT_EQ(Count(svg, 'M'), runs);  // a move per run of one side's bones
  EXPECT_EQ(FigureStrokes(layout).size(), 3u) << "centre, left and right";
  EXPECT_EQ(svg.find("<line"), std::string::npos);
  const std::regex long_decimal("[0-9]\\.[0-9][0-9]");
  EXPECT_FALSE(std::regex_search(svg, long_decimal)) << svg;
  EXPECT_LT(svg.size(), 800u) << "a figure stays small";
}

TEST(StickFigureSvg, RestPoseFitsTheBox) {
  const Skeleton skeleton = CmuBodyModel::Get().skeleton();
  FigureProjection projection;
  projection.pixels_per_unit = FigureScaleFor(skeleton, projection.height_px, projection.margin_px);
  const std::vector<Eigen::Vector3d> rest = RestPosePositions(skeleton);
  double floor = 1e9;
  for (const Eigen::Vector3d& point : rest) floor = std::min(floor, point.y());
  projection.origin = Eigen::Vector3d(0, floor, 0);
  for (FigureView view : {FigureView::kSide, FigureView::kFront}) {
    projection.view = view;
    for (const FigurePoint& point : ProjectPose(rest, projection)) {
      EXPECT_GE(point[1], projection.margin_px - 0.05);
      EXPECT_LE(point[1], projection.height_px - projection.margin_px + 0.05);
    }
  }
}

TEST(ProjectPose, RemovesTheHeading) {
  const Skeleton skeleton = Branchy();
  const std::vector<Eigen::Vector3d> rest = RestPosePositions(skeleton);
  const double heading = 1.1;
  const Eigen::Vector3d origin(3, 0, -2);
  std::vector<Eigen::Vector3d> turned;
  for (const Eigen::Vector3d& point : rest) {
    turned.push_back(origin + AxisRotation(Axis::kY, heading) * point);
  }
  FigureProjection projection;
  projection.pixels_per_unit = 10;
  const std::vector<FigurePoint> straight = ProjectPose(rest, projection);
  projection.heading_rad = heading;
  projection.origin = origin;
  const std::vector<FigurePoint> unturned = ProjectPose(turned, projection);
  ASSERT_EQ(straight.size(), unturned.size());
  for (size_t point_idx = 0; point_idx < straight.size(); ++point_idx) {
    EXPECT_NEAR(straight[point_idx][0], unturned[point_idx][0], 0.1 + 1e-9);
    EXPECT_NEAR(straight[point_idx][1], unturned[point_idx][1], 0.1 + 1e-9);
  }
  // Side view: +Z to the right; front view: +X to the right; up is up.
  EXPECT_GT(ProjectPose({Eigen::Vector3d(0, 0, 1)}, FigureProjection{})[0][0], kFigureWidthPx / 2);
  FigureProjection front;
  front.view = FigureView::kFront;
  EXPECT_GT(ProjectPose({Eigen::Vector3d(1, 0, 0)}, front)[0][0], kFigureWidthPx / 2);
  EXPECT_LT(ProjectPose({Eigen::Vector3d(0, 1, 0)}, front)[0][1],
            front.height_px - front.margin_px);
}

// The stroke colour of every segment of a figure's SVG, by its end points' text "x1 y1 x2 y2".
std::map<std::string, std::string> SegmentColours(const std::string& svg) {
  std::map<std::string, std::string> colours;
  const std::regex path("<path stroke=\"([^\"]+)\" d=\"([^\"]+)\"/>");
  const std::regex step("([ML])(-?[0-9.]+) (-?[0-9.]+)");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), path); it != std::sregex_iterator();
       ++it) {
    const std::string colour = (*it)[1];
    const std::string d = (*it)[2];
    std::string previous;
    for (auto at = std::sregex_iterator(d.begin(), d.end(), step); at != std::sregex_iterator();
         ++at) {
      const std::string here = (*at)[2].str() + " " + (*at)[3].str();
      if ((*at)[1] == "L") colours[previous + " " + here] = colour;
      previous = here;
    }
  }
  return colours;
}

// The colour the SVG strokes the bone that ends at joint `name` in: the front view of the rest
// pose, so left and right limbs do not overlap.
std::string BoneColour(const Skeleton& skeleton, const std::string& name) {
  const StickFigureLayout layout = MakeStickFigureLayout(skeleton);
  FigureProjection projection;
  projection.view = FigureView::kFront;
  projection.pixels_per_unit = FigureScaleFor(skeleton, projection.height_px, 6);
  const std::vector<FigurePoint> points =
      ProjectFigure(layout, RestPosePositions(skeleton), projection);
  const std::map<std::string, std::string> colours =
      SegmentColours(StickFigureSvg(layout, points, projection.width_px, projection.height_px));
  const auto text = [&](uint32_t point) {
    return FormatFigureCoord(points[point][0]) + " " + FormatFigureCoord(points[point][1]);
  };
  const int joint = skeleton.FindJoint(name);
  for (const std::vector<uint32_t>& chain : layout.chains) {
    for (size_t step = 1; step < chain.size(); ++step) {
      if (layout.points[chain[step]] != static_cast<uint32_t>(joint)) continue;
      const auto found = colours.find(text(chain[step - 1]) + " " + text(chain[step]));
      return found == colours.end() ? "not stroked" : found->second;
    }
  }
  return "not drawn";
}

// The strips colour limbs as the player does: left blue, right red, the spine grey (the one
// table of limb_side.h), for CMU's names and for a studio rig's "_L" / "_R" and Left / Right.
TEST(StickFigureSvg, StrokesLeftAndRightBonesInThePlayersColours) {
  EXPECT_STREQ(LimbSideColour(1), "#1f6fd1");
  EXPECT_STREQ(LimbSideColour(2), "#d62728");
  EXPECT_STREQ(LimbSideColour(0), "#555");
  const Skeleton cmu = CmuBodyModel::Get().skeleton();
  ASSERT_EQ(cmu.family(), "cmu31");
  for (const char* left : {"lfemur", "ltibia", "lhumerus", "lradius"}) {
    EXPECT_EQ(BoneColour(cmu, left), "#1f6fd1") << left;
  }
  for (const char* right : {"rfemur", "rtibia", "rhumerus", "rradius"}) {
    EXPECT_EQ(BoneColour(cmu, right), "#d62728") << right;
  }
  EXPECT_EQ(BoneColour(cmu, "upperback"), "#555");

  // Hips; legs UpperLeg_L / _R down to LowerLeg; a spine, and arms named Left/Right.
  std::vector<Joint> joints(9);
  joints[0].name = "Hips";
  joints[1] = {"UpperLeg_L", 0, {0.1, -0.1, 0}, false, {}, {}, 0};
  joints[2] = {"LowerLeg_L", 1, {0, -0.45, 0}, true, {0, -0.45, 0}, {}, 0};
  joints[3] = {"UpperLeg_R", 0, {-0.1, -0.1, 0}, false, {}, {}, 0};
  joints[4] = {"LowerLeg_R", 3, {0, -0.45, 0}, true, {0, -0.45, 0}, {}, 0};
  joints[5] = {"Spine", 0, {0, 0.5, 0}, false, {}, {}, 0};
  joints[6] = {"Head", 5, {0, 0.3, 0}, true, {0, 0.2, 0}, {}, 0};
  joints[7] = {"LeftArm", 5, {0.2, 0.2, 0}, true, {0.5, 0, 0}, {}, 0};
  joints[8] = {"RightArm", 5, {-0.2, 0.2, 0}, true, {-0.5, 0, 0}, {}, 0};
  const Skeleton studio("studio", joints);
  EXPECT_EQ(BoneColour(studio, "UpperLeg_L"), "#1f6fd1");
  EXPECT_EQ(BoneColour(studio, "LowerLeg_L"), "#1f6fd1");
  EXPECT_EQ(BoneColour(studio, "LeftArm"), "#1f6fd1");
  EXPECT_EQ(BoneColour(studio, "UpperLeg_R"), "#d62728");
  EXPECT_EQ(BoneColour(studio, "RightArm"), "#d62728");
  EXPECT_EQ(BoneColour(studio, "Head"), "#555");
}

TEST(EncodeFigurePoints, TwoCharactersPerCoordinateAndClamped) {
  EXPECT_EQ(EncodeFigurePoints({{kFigureCoordMin, kFigureCoordMax}}), "AA__");
  // 0 px = 1000 tenths above the minimum = 15 * 64 + 40: "P" "o".
  EXPECT_EQ(EncodeFigurePoints({{0.0, -1000.0}}), "PoAA");
  EXPECT_EQ(EncodeFigurePoints({{12.34, 5000.0}}), EncodeFigurePoints({{12.3, kFigureCoordMax}}));
}

TEST(FormatFigureCoord, AtMostOneDecimal) {
  EXPECT_EQ(FormatFigureCoord(12.0), "12");
  EXPECT_EQ(FormatFigureCoord(12.34), "12.3");
  EXPECT_EQ(FormatFigureCoord(-0.46), "-0.5");
  EXPECT_EQ(FormatFigureCoord(-0.04), "0");
  EXPECT_EQ(FormatFigureCoord(1e6), "309.5");
}

}  // namespace
}  // namespace motif
