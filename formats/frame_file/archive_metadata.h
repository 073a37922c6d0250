// ArchiveMetadata: everything a commit of a motion archive describes besides the frames
// themselves (docs/formats/frame_file.md, "Metadata"): the archive's rate and layout, the
// skeleton table, the column table (what each column chunk holds and how it is encoded), the
// clip table and the block index. Each commit writes all of it anew just before its footer, as a
// sequence of tagged sections:
//
//   section := tag u32 | reserved u32 (0) | payload_bytes u64 | payload
//   tags, strictly increasing: 1 ARCHIVE, 2 SKELETON, 3 COLUMNS, 4 CLIPS, 5 BLOCKS
//   (unknown tags, added by later minor versions, are skipped)
//
// DecodeFrom checks every structural invariant (see the spec's reader duties), so code that
// holds a decoded ArchiveMetadata may index with it without further checks.
// Thread-safety: values and pure functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "formats/frame_file/column_codec.h"
#include "formats/frame_file/frame_file_format.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/skeleton.h"

namespace motif::frame_file {

// Pinned values: stored in the column table.
enum class ColumnKind : uint8_t {
  kJointRotation = 0,  // 4 components: w x y z of joint `joint_idx`
  kRootHeight = 1,     // 1 component
  kRootVelocity = 2,   // 2 components: x z, in the heading frame
  kHeading = 3,        // 1 component, radians, unwrapped
};

inline constexpr uint32_t kNoJoint = 0xFFFFFFFFu;

enum class SectionTag : uint32_t {
  kArchive = 1,
  kSkeleton = 2,
  kColumns = 3,
  kClips = 4,
  kBlocks = 5,
};

// One column table entry (24 bytes on disk).
struct ColumnSpec {
  ColumnKind kind = ColumnKind::kJointRotation;
  uint8_t component_count = 0;
  uint32_t row_offset = 0;        // first float of the column in a frame row
  uint32_t joint_idx = kNoJoint;  // the joint of a kJointRotation column
  ColumnEncoding encoding;

  bool operator==(const ColumnSpec&) const = default;
};

// The quantisation steps of the default encodings. Each column: uniform quantisation, delta
// along time (order 2 for rotations, height and heading, order 1 for the root velocity), zigzag,
// byte shuffle, zstd; quaternions renormalised on decode. With `lossless`, every column keeps its
// float32 bits (delta 1, zigzag, shuffle, zstd) and nothing is normalised.
struct ColumnDefaults {
  double quaternion_step = 1.0 / 32768;  // 2^-15
  double height_step = 1e-4;             // length units
  double velocity_step = 1e-3;           // length units per second
  double heading_step = 1e-5;            // radians
  bool lossless = false;
};

// The column table the writer uses for a new archive: one kJointRotation column per joint, then
// root height, root velocity and heading, in row order.
std::vector<ColumnSpec> DefaultColumns(uint32_t joint_count, const ColumnDefaults& defaults);

struct ArchiveMetadata {
  double fps = 0;
  uint64_t frame_count = 0;
  uint32_t joint_count = 0;
  uint32_t block_frames = 0;  // the creating writer's nominal block size
  Skeleton skeleton;
  std::vector<ColumnSpec> columns;
  std::vector<ClipInfo> clips;
  std::vector<BlockHandle> blocks;

  FrameLayout layout() const { return FrameLayout{joint_count}; }

  void EncodeTo(std::string* out) const;
  // Parses `size` bytes found at `file_offset` (used in messages, and to check that every block
  // lies before the metadata) and checks every invariant. Corruption with a message naming the
  // section and the file offset.
  static Status DecodeFrom(const uint8_t* data, size_t size, uint64_t file_offset,
                           ArchiveMetadata* metadata);
};

// Checks a column table against a layout: valid encodings, known kinds with their component
// counts, and the columns cover every float of the row exactly once. InvalidArgument.
Status ValidateColumns(const std::vector<ColumnSpec>& columns, uint32_t joint_count);

}  // namespace motif::frame_file
