#include "formats/motion/body_retarget.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "formats/motion/body_landmarks.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/cmu_rest_pose.h"

namespace motif {
namespace {

using Vec = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;
using Mat = Eigen::Matrix3d;

// Below this sine of the angle between its bones a limb counts as straight: its hinge axis is
// carried over from the frame before (15 degrees).
constexpr double kStraightLimbSine = 0.2588;

int Canonical(const char* name) {
  const auto& names = CmuCanonicalJointNames();
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

// World positions of the joints of a skeleton posed by local rotations (root: world rotation).
std::vector<Vec> JointPositions(const Skeleton& skeleton, const Vec& root, const Quat* local,
                                std::vector<Quat>* world) {
  std::vector<Vec> positions(skeleton.joint_count());
  world->assign(skeleton.joint_count(), Quat::Identity());
  for (size_t joint = 0; joint < skeleton.joint_count(); ++joint) {
    const int parent = skeleton.joint(joint).parent;
    if (parent < 0) {
      positions[joint] = root;
      (*world)[joint] = local[joint];
      continue;
    }
    const auto& offset = skeleton.joint(joint).offset;
    positions[joint] = positions[parent] + (*world)[parent] * Vec(offset[0], offset[1], offset[2]);
    (*world)[joint] = (*world)[parent] * local[joint];
  }
  return positions;
}

// The rotation whose columns are `primary` made unit, `secondary` made orthogonal to it, and
// their cross product. A secondary along the primary is replaced by any perpendicular.
Mat Frame(const Vec& primary, const Vec& secondary) {
  const Vec x = primary.normalized();
  Vec y = secondary - secondary.dot(x) * x;
  if (y.norm() < 1e-9 * std::max(1.0, secondary.norm())) y = x.unitOrthogonal();
  y.normalize();
  Mat frame;
  frame.col(0) = x;
  frame.col(1) = y;
  frame.col(2) = x.cross(y);
  return frame;
}

// The world rotation that turns the rest frame (bone, reference) into the current one.
Quat Orientation(const Vec& rest_bone, const Vec& rest_reference, const Vec& bone,
                 const Vec& reference) {
  const Mat rotation = Frame(bone, reference) * Frame(rest_bone, rest_reference).transpose();
  return Quat(rotation).normalized();
}

// The canonical joints a limb drives, and its hinge axis carried from frame to frame.
struct LimbChain {
  int parent;  // canonical joint whose world rotation carries the axis of a straight limb
  int upper;   // canonical joints of the upper bone, the lower bone and the end bone (or -1)
  int lower;
  int end;
  int upper_end;  // canonical joint at the end of each bone (rest positions)
  int lower_end;
  int end_end;
  int source_start;  // source joints at the limb's start, middle, end and beyond (or -1)
  int source_middle;
  int source_end;
  int source_beyond;
  Vec rest_axis;
  std::optional<Vec> axis_in_parent;  // the last frame's axis in the parent's frame
};

// Each canonical joint's source joint (-1: none), for the rest-aligned mapping.
std::vector<int> SourceOfCanonical(const BodyLandmarks& body) {
  std::vector<int> source(CmuCanonicalJointNames().size(), -1);
  const auto map = [&](const std::string& name, int joint) {
    if (joint >= 0) source[Canonical(name.c_str())] = joint;
  };
  map("root", body.pelvis);
  if (!body.spine.empty()) map("lowerback", body.spine[0]);
  if (body.spine.size() >= 2) map("upperback", body.spine[1]);
  map("thorax", body.chest);
  if (!body.neck.empty()) map("lowerneck", body.neck[0]);
  if (body.neck.size() >= 2) map("upperneck", body.neck[1]);
  map("head", body.head);
  // The hip joints and clavicles stay unmapped: rigs split the pelvis-to-thigh and
  // chest-to-arm turn between those and the limb differently (a Daz collar turns far more than
  // a CMU clavicle), and the distance weighs the limb relative to its parent. Following the
  // pelvis and chest, the limb's rotation carries the whole turn.
  for (const auto& [prefix, limbs] : {std::pair{"l", &body.left}, std::pair{"r", &body.right}}) {
    const std::string side = prefix;
    map(side + "femur", limbs->hip);
    map(side + "tibia", limbs->knee);
    map(side + "foot", limbs->ankle);
    map(side + "toes", limbs->toes);
    map(side + "humerus", limbs->upper_arm);
    map(side + "radius", limbs->elbow);
    map(side + "wrist", limbs->wrist);
  }
  return source;
}

// The canonical joint that carries a joint's bone on (its main child), or -1.
int CanonicalChainChild(int canonical) {
  static const std::vector<int> children = [] {
    const std::pair<const char*, const char*> chains[] = {
        {"lhipjoint", "lfemur"},   {"lfemur", "ltibia"},       {"ltibia", "lfoot"},
        {"lfoot", "ltoes"},        {"rhipjoint", "rfemur"},    {"rfemur", "rtibia"},
        {"rtibia", "rfoot"},       {"rfoot", "rtoes"},         {"lowerback", "upperback"},
        {"upperback", "thorax"},   {"thorax", "lowerneck"},    {"lowerneck", "upperneck"},
        {"upperneck", "head"},     {"lclavicle", "lhumerus"},  {"lhumerus", "lradius"},
        {"lradius", "lwrist"},     {"rclavicle", "rhumerus"},  {"rhumerus", "rradius"},
        {"rradius", "rwrist"}};
    std::vector<int> table(CmuCanonicalJointNames().size(), -1);
    for (const auto& [joint, child] : chains) table[Canonical(joint)] = Canonical(child);
    return table;
  }();
  return children[canonical];
}

// The mapping for a rig whose zero rotations stand upright (a T- or A-pose: CMU, Daz): each
// canonical joint takes its source joint's world rotation, times the constant rotation that
// turns the canonical rest bone onto the source's rest bone (and the rest body frames onto each
// other); the joints the source lacks keep their rest rotation relative to their parent.
class RestAlignedMapping {
 public:
  RestAlignedMapping(const BodyLandmarks& body,
                     const std::vector<Vec>& source_rest, const std::vector<Vec>& canonical_rest)
      : source_of_(SourceOfCanonical(body)), corrections_(source_of_.size()) {
    const auto frame_of = [&](const std::vector<Vec>& at, int pelvis, int chest, int lhip, int rhip) {
      return std::pair{at[chest] - at[pelvis], at[lhip] - at[rhip]};
    };
    const auto [rest_up, rest_left] =
        frame_of(canonical_rest, 0, Canonical("thorax"), Canonical("lfemur"), Canonical("rfemur"));
    const auto [up, left] = frame_of(source_rest, body.pelvis, body.chest, body.left.hip,
                                     body.right.hip);
    const Quat body_frame = Orientation(rest_up, rest_left, up, left);
    for (size_t joint = 0; joint < source_of_.size(); ++joint) {
      corrections_[joint] = body_frame;
      if (source_of_[joint] < 0) continue;
      for (int child = CanonicalChainChild(static_cast<int>(joint)); child >= 0;
           child = CanonicalChainChild(child)) {
        if (source_of_[child] < 0) continue;
        const Vec rest_bone = canonical_rest[child] - canonical_rest[joint];
        const Vec bone = source_rest[source_of_[child]] - source_rest[source_of_[joint]];
        if (rest_bone.norm() > 1e-9 && bone.norm() > 1e-9) {
          corrections_[joint] = Quat::FromTwoVectors(body_frame * rest_bone, bone) * body_frame;
        }
        break;
      }
    }
  }

  // Sets the world rotation of each canonical joint that has a source joint, for a frame whose
  // source world rotations are `source_world`.
  void Pose(const std::vector<Quat>& source_world, std::vector<Quat>* world,
            std::vector<bool>* set) const {
    for (size_t joint = 0; joint < source_of_.size(); ++joint) {
      if (source_of_[joint] < 0) continue;
      (*world)[joint] = source_world[source_of_[joint]] * corrections_[joint];
      (*set)[joint] = true;
    }
  }

 private:
  std::vector<int> source_of_;
  std::vector<Quat> corrections_;
};

// True when the rig's zero rotations stand upright: the chest within 45 degrees of straight
// above the pelvis, each ankle within 45 degrees of straight below its hip.
bool StandsUprightAtRest(const BodyLandmarks& body, const std::vector<Vec>& rest) {
  const auto within = [](const Vec& direction, const Vec& axis) {
    return direction.norm() > 0 && direction.normalized().dot(axis) > std::cos(M_PI / 4);
  };
  return within(rest[body.chest] - rest[body.pelvis], Vec::UnitY()) &&
         within(rest[body.left.ankle] - rest[body.left.hip], -Vec::UnitY()) &&
         within(rest[body.right.ankle] - rest[body.right.hip], -Vec::UnitY());
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
        out.rotations.push_back(parent < 0 ? world[joint]
                                           : (world[parent].conjugate() * world[joint]).normalized());
      }
    }
    return out;
  }

 private:
  Vec Rest(int canonical) const { return rest_positions_[canonical]; }

  LimbChain Arm(const LimbJoints& side, const std::string& prefix, const Vec& axis) const {
    return {Canonical((prefix + "clavicle").c_str()), Canonical((prefix + "humerus").c_str()),
            Canonical((prefix + "radius").c_str()),   -1,
            Canonical((prefix + "radius").c_str()),   Canonical((prefix + "wrist").c_str()),
            -1,                                       side.upper_arm,
            side.elbow,                               side.wrist,
            -1,                                       axis,
            std::nullopt};
  }

  LimbChain Leg(const LimbJoints& side, const std::string& prefix, const Vec& axis) const {
    const bool toes = side.toes >= 0;
    return {Canonical((prefix + "hipjoint").c_str()),
            Canonical((prefix + "femur").c_str()),
            Canonical((prefix + "tibia").c_str()),
            toes ? Canonical((prefix + "foot").c_str()) : -1,
            Canonical((prefix + "tibia").c_str()),
            Canonical((prefix + "foot").c_str()),
            toes ? Canonical((prefix + "toes").c_str()) : -1,
            side.hip,
            side.knee,
            side.ankle,
            side.toes,
            axis,
            std::nullopt};
  }

  // The source's size over the rest body's, by leg length (hip to ankle).
  double SourceScale() const {
    const auto length = [&](int joint) {
      const auto& o = take_.skeleton.joint(joint).offset;
      return Vec(o[0], o[1], o[2]).norm();
    };
    const double source = length(body_.left.knee) + length(body_.left.ankle) +
                          length(body_.right.knee) + length(body_.right.ankle);
    const double rest = (Rest(Canonical("ltibia")) - Rest(Canonical("lfemur"))).norm() +
                        (Rest(Canonical("lfoot")) - Rest(Canonical("ltibia"))).norm() +
                        (Rest(Canonical("rtibia")) - Rest(Canonical("rfemur"))).norm() +
                        (Rest(Canonical("rfoot")) - Rest(Canonical("rtibia"))).norm();
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
    const Vec hips = at[body_.left.hip] - at[body_.right.hip];
    const Vec shoulders = at[body_.left.upper_arm] - at[body_.right.upper_arm];
    const Vec rest_hips = Rest(Canonical("lfemur")) - Rest(Canonical("rfemur"));
    const Vec rest_shoulders = Rest(Canonical("lhumerus")) - Rest(Canonical("rhumerus"));
    put(0, Orientation(Rest(Canonical("thorax")) - Rest(0), rest_hips,
                       at[body_.chest] - at[body_.pelvis], hips));
    const int lowerback = Canonical("lowerback");
    const int upperback = Canonical("upperback");
    const int thorax = Canonical("thorax");
    const std::vector<int>& spine = body_.spine;
    if (spine.size() >= 2) {
      put(lowerback, Orientation(Rest(upperback) - Rest(lowerback), rest_hips,
                                 at[spine[1]] - at[spine[0]], hips));
      put(upperback, Orientation(Rest(thorax) - Rest(upperback), rest_shoulders,
                                 at[body_.chest] - at[spine[1]], shoulders));
    } else if (spine.size() == 1) {
      put(lowerback, Orientation(Rest(thorax) - Rest(lowerback), rest_hips,
                                 at[body_.chest] - at[spine[0]], hips));
    }
    const int head = Canonical("head");
    put(thorax, Orientation(Rest(head) - Rest(thorax), rest_shoulders,
                            at[body_.head] - at[body_.chest], shoulders));
  }

  // The arms and legs, once the root and thorax are set: the clavicles and hip joints follow
  // those, the bones below them point where the source's do.
  void PoseLimbs(const std::vector<Vec>& at, std::vector<Quat>* world, std::vector<bool>* set) {
    for (LimbChain& limb : limbs_) {
      if (!(*set)[limb.parent]) (*world)[limb.parent] = (*world)[rest_.joint(limb.parent).parent];
      const Vec upper = at[limb.source_middle] - at[limb.source_start];
      const Vec lower = at[limb.source_end] - at[limb.source_middle];
      const Vec axis = HingeAxis(upper, lower, (*world)[limb.parent], &limb);
      const auto pose = [&](int joint, int joint_end, const Vec& bone) {
        (*world)[joint] = Orientation(Rest(joint_end) - Rest(joint), limb.rest_axis, bone, axis);
        (*set)[joint] = true;
      };
      pose(limb.upper, limb.upper_end, upper);
      pose(limb.lower, limb.lower_end, lower);
      if (limb.end >= 0) pose(limb.end, limb.end_end, at[limb.source_beyond] - at[limb.source_end]);
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
  std::array<LimbChain, 4> limbs_;
  std::optional<RestAlignedMapping> rest_aligned_;  // set when the rig stands upright at rest
};

}  // namespace

Result<Take> RetargetToCmuBody(const Take& take) {
  Result<BodyLandmarks> body = FindBodyLandmarks(take.skeleton);
  if (!body.ok()) {
    return Status::InvalidArgument(take.source_path + ": its skeleton (" +
                                   std::to_string(take.joint_count()) +
                                   " joints) cannot be mapped onto the CMU body: " +
                                   body.status().message());
  }
  return BodyRetargeter(take, *body).Run();
}

}  // namespace motif
