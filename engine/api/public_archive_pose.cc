// motifmine::Archive's pose: its skeletons, the root of a frame range and the joints' world
// positions (include/motifmine/archive.h). The root is rebuilt by the code `motifmine export`
// plays (ReadClipRangeAsTake over ClipFramesToTake, formats/motion/pose_frames.h), the
// positions by the report's forward kinematics, so neither is a second copy of the conversion.
#include <utility>

#include "engine/api/archive_impl.h"
#include "engine/api/public_status.h"
#include "engine/report/forward_kinematics.h"
#include "formats/frame_file/clip_range_take.h"
#include "motifmine/archive.h"

namespace motifmine {
namespace {

// The archive skeleton with the canonical names standing for the source's.
Skeleton PublicSkeleton(const motif::Skeleton& skeleton) {
  Skeleton out;
  out.family = skeleton.family();
  for (const motif::Joint& joint : skeleton.joints()) {
    out.joint_names.push_back(joint.name);
    out.parents.push_back(joint.parent);
    out.offsets.push_back(joint.offset);
  }
  out.source_joint_names = out.joint_names;
  return out;
}

// A clip's source names, or the canonical ones where it kept them (Take::source_joint_names).
std::vector<std::string> SourceNames(const motif::ClipInfo& clip,
                                     const std::vector<std::string>& canonical) {
  return clip.source_joint_names.size() == canonical.size() ? clip.source_joint_names : canonical;
}

// The frames of a range as a Take, as export reads it; an empty range is an empty take.
Status RangeTake(const motif::FrameFileReader& reader, const motif::ClipInfo& clip, uint64_t start,
                 uint64_t end, motif::Take* take) {
  if (start == end) return {};
  motif::Result<motif::Take> read = motif::ReadClipRangeAsTake(reader, clip, start, end);
  if (!read.ok()) return motif::ToPublicStatus(read.status());
  *take = std::move(read).value();
  return {};
}

}  // namespace

Skeleton Archive::skeleton() const {
  Skeleton out = PublicSkeleton(impl_->reader->skeleton());
  const std::vector<std::string> canonical = out.joint_names;
  for (size_t clip_idx = 0; clip_idx < impl_->reader->clips().size(); ++clip_idx) {
    const std::vector<std::string> names = SourceNames(impl_->reader->clips()[clip_idx], canonical);
    if (clip_idx == 0) out.source_joint_names = names;
    for (size_t joint_idx = 0; joint_idx < names.size(); ++joint_idx) {
      if (names[joint_idx] != out.source_joint_names[joint_idx]) {
        out.source_joint_names[joint_idx] = canonical[joint_idx];  // the clips disagree
      }
    }
  }
  return out;
}

Status Archive::ClipSkeleton(const std::string& clip, Skeleton* skeleton) const {
  const motif::ClipInfo* info = nullptr;
  if (Status found = impl_->FindClip(clip, &info); !found.ok()) return found;
  *skeleton = PublicSkeleton(impl_->reader->skeleton());
  skeleton->source_joint_names = SourceNames(*info, skeleton->joint_names);
  // The clip's own bone lengths where it has them, as ClipFramesToTake puts them in.
  for (size_t joint_idx = 0;
       joint_idx < info->joint_offsets.size() && joint_idx < skeleton->offsets.size();
       ++joint_idx) {
    for (int axis = 0; axis < 3; ++axis) {
      skeleton->offsets[joint_idx][axis] = info->joint_offsets[joint_idx][axis];
    }
  }
  return {};
}

Status Archive::Root(const std::string& clip, uint64_t start, uint64_t end,
                     RootMotion* root) const {
  const motif::ClipInfo* info = nullptr;
  if (Status in_clip = impl_->FindRange(clip, start, end, &info); !in_clip.ok()) return in_clip;
  motif::Take take;
  if (Status read = RangeTake(*impl_->reader, *info, start, end, &take); !read.ok()) return read;
  // The stored heading itself (unwrapped along the clip), not one taken back from the rotation.
  std::vector<float> rows;
  motif::Status headings = impl_->reader->ReadFrames(info->first_frame + start, end - start, &rows);
  if (!headings.ok()) return motif::ToPublicStatus(headings);
  const motif::FrameLayout layout = impl_->reader->layout();
  *root = RootMotion();
  for (size_t frame_idx = 0; frame_idx < take.frame_count(); ++frame_idx) {
    const Eigen::Vector3d& position = take.root_positions[frame_idx];
    const Eigen::Quaterniond& rotation = take.rotation(frame_idx, 0);
    root->positions.insert(root->positions.end(), {position.x(), position.y(), position.z()});
    root->rotations.insert(root->rotations.end(),
                           {rotation.w(), rotation.x(), rotation.y(), rotation.z()});
    root->headings.push_back(rows[frame_idx * layout.stride() + layout.heading_offset()]);
  }
  return {};
}

Status Archive::WorldPositions(const std::string& clip, uint64_t start, uint64_t end,
                               std::vector<double>* positions) const {
  const motif::ClipInfo* info = nullptr;
  if (Status in_clip = impl_->FindRange(clip, start, end, &info); !in_clip.ok()) return in_clip;
  motif::Take take;
  if (Status read = RangeTake(*impl_->reader, *info, start, end, &take); !read.ok()) return read;
  positions->clear();
  positions->reserve(take.frame_count() * take.joint_count() * 3);
  for (size_t frame_idx = 0; frame_idx < take.frame_count(); ++frame_idx) {
    const std::vector<Eigen::Vector3d> points = motif::TakeFramePositions(take, frame_idx);
    for (size_t joint_idx = 0; joint_idx < take.joint_count(); ++joint_idx) {
      positions->insert(positions->end(),
                        {points[joint_idx].x(), points[joint_idx].y(), points[joint_idx].z()});
    }
  }
  return {};
}

}  // namespace motifmine
