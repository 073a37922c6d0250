#include "formats/motion/body_retarget.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "formats/motion/body_kinematics.h"
#include "formats/motion/body_landmarks.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/cmu_rest_pose.h"
#include "formats/motion/rest_aligned_mapping.h"

namespace motif {
namespace {

using Vec = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

// Below this sine of the angle between its bones a limb counts as straight: its hinge axis is
// carried over from the frame before (15 degrees).
constexpr double kStraightLimbSine = 0.2588;

// The canonical names of a limb's joints, after the side's prefix "l" / "r".
struct LimbNames {
  const char* parent;
  const char* upper;
  const char* lower;
  const char* end;
  const char* beyond;  // where the end bone ends, when the source has one
};
constexpr LimbNames kArmNames = {"clavicle", "humerus", "radius", "wrist", nullptr};
constexpr LimbNames kLegNames = {"hipjoint", "femur", "tibia", "foot", "toes"};

// The canonical joints a limb drives, the source joints it follows, and its hinge axis carried
// from frame to frame.
struct LimbChain {
  int parent;  // canonical joint whose world rotation carries the axis of a straight limb
  int upper;   // canonical joints where the upper, lower and end bones start
  int lower;
  int end;
  int beyond;        // canonical joint where the end bone ends; -1: none (arms, legs without toes)
  int source_start;  // source joints at the limb's start, middle, end and beyond (or -1)
  int source_middle;
  int source_end;
  int source_beyond;
  Vec rest_upper = Vec::Zero();  // the rest bones, from each start to the next
  Vec rest_lower = Vec::Zero();
  Vec rest_end = Vec::Zero();
  Vec rest_axis;
  std::optional<Vec> axis_in_parent;  // the last frame's axis in the parent's frame
};

// The rest bones and frames the torso of a folded rig is placed by.
struct TorsoRest {
  int lowerback;
  int upperback;
  int thorax;
  Vec hips;         // right hip to left hip
  Vec shoulders;    // right shoulder to left shoulder
  Vec pelvis;       // root to thorax
  Vec lower_spine;  // lowerback to upperback
  Vec whole_spine;  // lowerback to thorax, for a source with one spine joint
  Vec upper_spine;  // upperback to thorax
  Vec neck;         // thorax to head
};

TorsoRest RestTorso(const std::vector<Vec>& rest) {
  const auto at = [&](const char* name) { return rest[CanonicalJointIndex(name)]; };
  TorsoRest torso;
  torso.lowerback = CanonicalJointIndex("lowerback");
  torso.upperback = CanonicalJointIndex("upperback");
  torso.thorax = CanonicalJointIndex("thorax");
  torso.hips = at("lfemur") - at("rfemur");
  torso.shoulders = at("lhumerus") - at("rhumerus");
  torso.pelvis = at("thorax") - rest[0];
  torso.lower_spine = at("upperback") - at("lowerback");
  torso.whole_spine = at("thorax") - at("lowerback");
  torso.upper_spine = at("thorax") - at("upperback");
  torso.neck = at("head") - at("thorax");
  return torso;
}

class BodyRetargeter {
 public:
  BodyRetargeter(const Take& take, const BodyLandmarks& body)
      : take_(take), body_(body), rest_(CmuRestSkeleton()) {
    std::vector<Quat> identity(rest_.joint_count(), Quat::Identity());
    std::vector<Quat> unused;
    rest_positions_ = JointPositions(rest_, Vec::Zero(), identity.data(), &unused);
    std::vector<Quat> source_identity(take.joint_count(), Quat::Identity());
    const std::vector<Vec> source_rest =
        JointPositions(take.skeleton, Vec::Zero(), source_identity.data(), &unused);
    if (StandsUprightAtRest(body, source_rest)) {
      rest_aligned_.emplace(body, source_rest, rest_positions_);
    }
    torso_ = RestTorso(rest_positions_);
    const CmuHingeAxes& axes = CmuRestHingeAxes();
    limbs_ = {Arm(body.left, "l", axes.left_elbow), Arm(body.right, "r", axes.right_elbow),
              Leg(body.left, "l", axes.left_knee), Leg(body.right, "r", axes.right_knee)};
  }

  Take Run() {
    Take out;
    out.name = take_.name;
    out.source_path = take_.source_path;
    out.fps = take_.fps;
    out.source_fps = take_.source_fps;
    // At the rest body's size: heights, speeds and figures compare across families.
    const double scale = SourceScale();
    out.meters_per_unit = take_.meters_per_unit * scale;
    out.content_hash = take_.content_hash;
    out.source_first_frame = take_.source_first_frame;
    out.description = take_.description;
    out.skeleton = rest_;
    for (const Vec& root : take_.root_positions) out.root_positions.push_back(root / scale);
    out.rotations.reserve(take_.frame_count() * rest_.joint_count());
    std::vector<Quat> source_world;
    for (size_t frame = 0; frame < take_.frame_count(); ++frame) {
      const std::vector<Vec> where =
          JointPositions(take_.skeleton, take_.root_positions[frame],
                         &take_.rotations[frame * take_.joint_count()], &source_world);
      const std::vector<Quat> world = CanonicalWorld(where, source_world);
      for (size_t joint = 0; joint < rest_.joint_count(); ++joint) {
        const int parent = rest_.joint(joint).parent;
        out.rotations.push_back(
            parent < 0 ? world[joint] : (world[parent].conjugate() * world[joint]).normalized());
      }
    }
    return out;
  }

 private:
  Vec Rest(int canonical) const { return rest_positions_[canonical]; }

  LimbChain Arm(const LimbJoints& side, const std::string& prefix, const Vec& axis) const {
    return Chain(kArmNames, prefix, {side.upper_arm, side.elbow, side.wrist, -1}, axis);
  }

  LimbChain Leg(const LimbJoints& side, const std::string& prefix, const Vec& axis) const {
    return Chain(kLegNames, prefix, {side.hip, side.knee, side.ankle, side.toes}, axis);
  }

  // `source`: the source joints at the limb's start, middle, end and beyond (-1: no end bone).
  LimbChain Chain(const LimbNames& names, const std::string& prefix,
                  const std::array<int, 4>& source, const Vec& axis) const {
    const auto canonical = [&](const char* name) {
      return CanonicalJointIndex((prefix + name).c_str());
    };
    LimbChain limb{.parent = canonical(names.parent),
                   .upper = canonical(names.upper),
                   .lower = canonical(names.lower),
                   .end = canonical(names.end),
                   .beyond = source[3] >= 0 ? canonical(names.beyond) : -1,
                   .source_start = source[0],
                   .source_middle = source[1],
                   .source_end = source[2],
                   .source_beyond = source[3],
                   .rest_axis = axis};
    limb.rest_upper = Rest(limb.lower) - Rest(limb.upper);
    limb.rest_lower = Rest(limb.end) - Rest(limb.lower);
    if (limb.beyond >= 0) limb.rest_end = Rest(limb.beyond) - Rest(limb.end);
    return limb;
  }

  // The source's size over the rest body's, by leg length (hip to ankle).
  double SourceScale() const {
    const auto length = [&](int joint) {
      const auto& o = take_.skeleton.joint(joint).offset;
      return Vec(o[0], o[1], o[2]).norm();
    };
    const double source = length(body_.left.knee) + length(body_.left.ankle) +
                          length(body_.right.knee) + length(body_.right.ankle);
    const double rest =
        (Rest(CanonicalJointIndex("ltibia")) - Rest(CanonicalJointIndex("lfemur"))).norm() +
        (Rest(CanonicalJointIndex("lfoot")) - Rest(CanonicalJointIndex("ltibia"))).norm() +
        (Rest(CanonicalJointIndex("rtibia")) - Rest(CanonicalJointIndex("rfemur"))).norm() +
        (Rest(CanonicalJointIndex("rfoot")) - Rest(CanonicalJointIndex("rtibia"))).norm();
    return source > 0 ? source / rest : 1.0;
  }

  // Every canonical joint's world rotation for one frame: the source's joint positions `at` and
  // world rotations `source_world`.
  std::vector<Quat> CanonicalWorld(const std::vector<Vec>& at,
                                   const std::vector<Quat>& source_world) {
    std::vector<Quat> world(rest_.joint_count(), Quat::Identity());
    std::vector<bool> set(rest_.joint_count(), false);
    if (rest_aligned_) {
      rest_aligned_->Pose(source_world, &world, &set);
    } else {
      PoseTorso(at, &world, &set);
    }
    PoseLimbs(at, &world, &set);
    // The rest keep their rest rotation relative to their parent (parents come first).
    for (size_t joint = 1; joint < rest_.joint_count(); ++joint) {
      if (!set[joint]) world[joint] = world[rest_.joint(joint).parent];
    }
    return world;
  }

  // The pelvis, spine and chest from where the source's joints are.
  void PoseTorso(const std::vector<Vec>& at, std::vector<Quat>* world, std::vector<bool>* set) {
    const auto put = [&](int joint, const Quat& rotation) {
      (*world)[joint] = rotation;
      (*set)[joint] = true;
    };
    const TorsoRest& rest = torso_;
    const Vec hips = at[body_.left.hip] - at[body_.right.hip];
    const Vec shoulders = at[body_.left.upper_arm] - at[body_.right.upper_arm];
    put(0, Orientation(rest.pelvis, rest.hips, at[body_.chest] - at[body_.pelvis], hips));
    const std::vector<int>& spine = body_.spine;
    if (spine.size() >= 2) {
      put(rest.lowerback,
          Orientation(rest.lower_spine, rest.hips, at[spine[1]] - at[spine[0]], hips));
      put(rest.upperback,
          Orientation(rest.upper_spine, rest.shoulders, at[body_.chest] - at[spine[1]], shoulders));
    } else if (spine.size() == 1) {
      put(rest.lowerback,
          Orientation(rest.whole_spine, rest.hips, at[body_.chest] - at[spine[0]], hips));
    }
    put(rest.thorax,
        Orientation(rest.neck, rest.shoulders, at[body_.head] - at[body_.chest], shoulders));
  }

  // The arms and legs, once the root and thorax are set: the clavicles and hip joints follow
  // those, the bones below them point where the source's do.
  void PoseLimbs(const std::vector<Vec>& at, std::vector<Quat>* world, std::vector<bool>* set) {
    for (LimbChain& limb : limbs_) {
      if (!(*set)[limb.parent]) (*world)[limb.parent] = (*world)[rest_.joint(limb.parent).parent];
      const Vec upper = at[limb.source_middle] - at[limb.source_start];
      const Vec lower = at[limb.source_end] - at[limb.source_middle];
      const Vec axis = HingeAxis(upper, lower, (*world)[limb.parent], &limb);
      const auto pose = [&](int joint, const Vec& rest_bone, const Vec& bone) {
        (*world)[joint] = Orientation(rest_bone, limb.rest_axis, bone, axis);
        (*set)[joint] = true;
      };
      pose(limb.upper, limb.rest_upper, upper);
      pose(limb.lower, limb.rest_lower, lower);
      if (limb.beyond >= 0) {
        pose(limb.end, limb.rest_end, at[limb.source_beyond] - at[limb.source_end]);
      }
      (*set)[limb.parent] = true;
    }
  }

  // The limb's hinge axis this frame: upper x lower where the limb bends, else the last
  // frame's (or the rest axis) carried by the parent; its sign kept continuous.
  static Vec HingeAxis(const Vec& upper, const Vec& lower, const Quat& parent, LimbChain* limb) {
    const Vec carried = parent * limb->axis_in_parent.value_or(limb->rest_axis);
    const Vec cross = upper.cross(lower);
    const double scale = upper.norm() * lower.norm();
    Vec axis = carried;
    if (scale > 0 && cross.norm() > kStraightLimbSine * scale) {
      axis = cross.normalized();
      if (axis.dot(carried) < 0) axis = -axis;
    }
    limb->axis_in_parent = parent.conjugate() * axis;
    return axis;
  }

  const Take& take_;
  const BodyLandmarks& body_;
  const Skeleton& rest_;
  std::vector<Vec> rest_positions_;
  TorsoRest torso_;
  std::array<LimbChain, 4> limbs_;
  std::optional<RestAlignedMapping> rest_aligned_;  // set when the rig stands upright at rest
};

}  // namespace

Result<Take> RetargetToCmuBody(const Take& take) {
  Result<BodyLandmarks> body = FindBodyLandmarks(take.skeleton);
  if (!body.ok()) {
    return Status::InvalidArgument(
        take.source_path + ": its skeleton (" + std::to_string(take.joint_count()) +
        " joints) cannot be mapped onto the CMU body: " + body.status().message());
  }
  return BodyRetargeter(take, *body).Run();
}

}  // namespace motif
