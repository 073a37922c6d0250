// motifmine::Archive, a motion archive (.mfs, docs/formats/frame_file.md) opened for reading,
// and motifmine::ImportTakes, which creates or appends to one. Part of the public API
// (<motifmine/motifmine.h>); no third-party type.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "motifmine/export.h"
#include "motifmine/status.h"

namespace motifmine {

struct Clip {
  std::string name;
  std::string source;  // the take file it was imported from ("synthetic" for the built-in one)
  uint64_t first_frame = 0;  // global frame index of its first frame
  uint64_t frames = 0;
  double fps = 0;
};

// A skeleton: its joints in frame order, parents first (joint 0 is the root).
struct Skeleton {
  std::string family;                    // "cmu31" (CMU's 31 joints) or "custom"
  std::vector<std::string> joint_names;  // the archive's names (canonical: "lfemur")
  // The names of the file the take was imported from ("LeftUpLeg" for a BVH take's "lfemur"),
  // as `motifmine export` writes them; the canonical name where the import kept the name.
  std::vector<std::string> source_joint_names;
  std::vector<int32_t> parents;                // -1 for the root
  std::vector<std::array<double, 3>> offsets;  // from the parent, rest pose, the take's units
};

// The root of frames [start, end) of a clip: what a pose needs beyond the joints' rotations.
struct RootMotion {
  std::vector<double> positions;  // frames x 3: world position, as `motifmine export` writes it
  std::vector<double> rotations;  // frames x 4: world rotation (w, x, y, z), heading included
  std::vector<double> headings;   // frames: radians about the vertical Y axis, unwrapped
};

// Whether this thread's calls (Archive::Open, Mine, BuildWords, LoadSignatures,
// SearchClipRange, ImportTakes) may work on an archive at its previous version when its newest
// commit is damaged. By default they may not: they fail with Corruption, naming the damage, as
// the motifmine tool does without --allow-older (docs/guide.md, "Damaged archives"). Returns
// the setting it replaces.
MOTIFMINE_API bool AllowOlderVersions(bool allow);

class MOTIFMINE_API Archive {
 public:
  // Opens the newest version of the archive at `path` (memory-mapped, read-only). NotFound,
  // Corruption (a damaged newest commit, unless AllowOlderVersions: docs/guide.md, "Damaged
  // archives"), NotSupported.
  static Status Open(const std::string& path, std::unique_ptr<Archive>* archive);
  ~Archive();
  Archive(const Archive&) = delete;
  Archive& operator=(const Archive&) = delete;

  const std::string& path() const;
  uint64_t frames() const;
  double fps() const;
  const std::vector<Clip>& clips() const;
  std::vector<std::string> joint_names() const;  // the skeleton's joints, in frame order
  // The archive's skeleton (its skeleton table): canonical joint names and the archive's rest
  // offsets; source_joint_names are those all its clips share, the canonical names where
  // clips imported from different kinds of file name a joint differently.
  Skeleton skeleton() const;

  // `clip`'s own skeleton: its source joint names and its bone offsets (subjects differ in
  // bone lengths), as `motifmine export` writes them. NotFound for an unknown clip.
  Status ClipSkeleton(const std::string& clip, Skeleton* skeleton) const;

  // The root of frames [start, end) of `clip`: positions integrated from the clip's first frame
  // by the code `motifmine export` uses (formats/motion/pose_frames.h), so frames [0, end) are
  // read. NotFound for an unknown clip, InvalidArgument for a range outside it.
  Status Root(const std::string& clip, uint64_t start, uint64_t end, RootMotion* root) const;

  // The world positions of the joints of frames [start, end) of `clip`: (end - start) x joints x
  // 3 doubles, by forward kinematics over the clip's own skeleton (the root at its position, a
  // joint at its parent's position plus its offset turned by the parent's world rotation).
  // Errors as Root.
  Status WorldPositions(const std::string& clip, uint64_t start, uint64_t end,
                        std::vector<double>* positions) const;

  // The joints' rotations of frames [start, end) of `clip` (frames within the clip, end
  // exclusive): (end - start) x joints x 4 floats, unit quaternions (w, x, y, z), each joint's
  // relative to its parent, the root's without its heading (about the vertical Y axis).
  // NotFound for an unknown clip, InvalidArgument for a range outside it.
  Status Rotations(const std::string& clip, uint64_t start, uint64_t end,
                   std::vector<float>* rotations) const;

 private:
  class Impl;
  explicit Archive(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

struct ImportOptions {
  bool skip_bad = false;  // pass over takes that fail (named in ImportResult::skipped)
  int threads = 0;        // 0: all cores
};

struct ImportResult {
  uint64_t takes_imported = 0;
  uint64_t takes_already_present = 0;
  uint64_t takes_mapped = 0;  // of those imported: other skeletons, mapped onto the CMU body
  uint64_t frames_added = 0;
  std::vector<std::string> skipped;  // skip_bad: the takes passed over, with the reason
};

// Imports BVH / ASF+AMC takes and folders into the archive at `archive_path` (created if
// missing), as `motifmine import` does: one commit, nothing changed on failure.
MOTIFMINE_API Status ImportTakes(const std::string& archive_path,
                                 const std::vector<std::string>& paths,
                                 const ImportOptions& options, ImportResult* result);

}  // namespace motifmine
