// The per-frame representation every stage of motifmine works on, and its conversion from and to
// a Take. A frame is a row of floats (FrameLayout):
//
//   [q_0.w q_0.x q_0.y q_0.z] ... [q_{J-1}.w .. q_{J-1}.z] [height] [vel_x vel_z] [heading]
//
// q_j is joint j's rest-aligned rotation relative to its parent; for the root (j = 0) it is the
// root's world rotation with the heading removed (the swing in q = Ry(heading) * swing). Signs
// are continuous along a clip (q_t . q_{t-1} >= 0), the first frame has w >= 0. height is the
// root's Y; (vel_x, vel_z) the root's horizontal velocity in the heading frame, in length units
// per second (frame 0 repeats frame 1's); heading is in radians, unwrapped along the clip.
// ClipInfo carries what a clip needs beyond its rows: where it starts, its bone lengths.
// Thread-safety: pure functions and value types.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/motion/skeleton.h"
#include "formats/motion/take.h"

namespace motif {

struct FrameLayout {
  uint32_t joint_count = 0;

  size_t stride() const { return 4 * static_cast<size_t>(joint_count) + 4; }
  size_t quaternion_offset(size_t joint_idx) const { return 4 * joint_idx; }
  size_t height_offset() const { return 4 * static_cast<size_t>(joint_count); }
  size_t velocity_offset() const { return 4 * static_cast<size_t>(joint_count) + 1; }
  size_t heading_offset() const { return 4 * static_cast<size_t>(joint_count) + 3; }
};

// One clip of an archive, as in its clip table (docs/formats/frame_file.md).
struct ClipInfo {
  std::string name;  // source file stem
  std::string source_path;
  uint64_t first_frame = 0;  // global index of the clip's first frame in the archive
  uint64_t frame_count = 0;
  double fps = 120.0;                      // the archive's rate (the clip is stored at it)
  double source_fps = 120.0;               // the source file's rate before resampling
  double meters_per_unit = 0;              // 0 if unknown
  uint64_t content_hash = 0;               // XXH3-64 of the source bytes, 0 for synthetic clips
  std::array<double, 3> start_position{};  // root world position at the clip's first frame
  uint64_t source_first_frame = 0;         // Take::source_first_frame
  std::vector<std::string> source_joint_names;  // Take::source_joint_names (empty: the same)
  std::string description;                      // Take::description
  // Per joint (archive skeleton order): this clip's bone offsets and end sites. Subjects differ
  // in bone lengths, so export uses the clip's own.
  std::vector<std::array<float, 3>> joint_offsets;
  std::vector<std::array<float, 3>> end_sites;
};

// A clip's frames in memory: `rows` holds frame_count * layout.stride() floats.
struct ClipFrames {
  ClipInfo info;
  std::vector<float> rows;
};

// Converts a take (already mapped to the archive's skeleton and resampled to its rate) into rows.
// info.first_frame is left 0: the archive writer assigns it.
ClipFrames TakeToClipFrames(const Take& take);

// Rebuilds world motion from rows [0, frame_count) of a clip: root positions (integrating the
// velocity from info.start_position), full root rotations (heading put back) and joint
// rotations. `skeleton` is the archive's; the clip's own offsets replace its joint offsets.
Take ClipFramesToTake(const Skeleton& skeleton, const ClipInfo& info, const float* rows,
                      size_t frame_count);

}  // namespace motif
