// FrameFileWriter: creates a motion archive (.mfs, docs/formats/frame_file.md) or appends clips to
// an existing one. Frames are buffered into column blocks of `block_frames` consecutive frames
// (blocks may span clip boundaries); each full block is compressed column by column and written
// at the end of the file, so memory stays bounded whatever the archive's size.
//
// Durability: nothing becomes visible until Commit(). Creating writes a temporary file beside the
// target and renames it into place on Commit(). Appending never rewrites existing blocks: new
// blocks, a new metadata section and a new footer go after the committed end, then the older of
// the header's two commit slots is overwritten to point at the new footer. A failure or a crash
// at any point before that slot write is durable leaves the previous archive readable and
// unchanged; an abandoned writer (destroyed without Commit) truncates its uncommitted tail.
// Only one writer may have an archive open: a second one gets Busy ("locked").
// Thread-safety: one thread at a time.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/status.h"
#include "common/writable_file.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/skeleton.h"

namespace motif {

struct FrameFileWriterOptions {
  uint32_t block_frames = 4096;  // frames per column block (the last block may be shorter)
  int zstd_level = 3;
  FileSystem* file_system = PosixFileSystem();  // tests inject failures here

  // Column encodings of a new archive (Create only; appends keep the archive's own, recorded in
  // its column table). Each column is quantised with its step (error <= step / 2 per value;
  // quaternions are renormalised on decode, rotation error <= 4 * quaternion_step), then delta
  // coded along time (order 2; order 1 for the root velocity), zigzag, byte shuffle and zstd.
  // With `lossless`, the float32 bits are kept exactly instead.
  double quaternion_step = 1.0 / 32768;  // 2^-15
  double height_step = 1e-4;             // length units
  double velocity_step = 1e-3;           // length units per second
  double heading_step = 1e-5;            // radians
  bool lossless = false;
};

class FrameFileWriter {
 public:
  // Starts a new archive at `path` (which must not exist: InvalidArgument otherwise) for takes of
  // `skeleton` at `fps` frames per second.
  static Result<std::unique_ptr<FrameFileWriter>> Create(
      const std::string& path, const Skeleton& skeleton, double fps,
      const FrameFileWriterOptions& options = {});
  // Opens an existing archive to append clips. Validates it first (Corruption / NotFound), and
  // discards an uncommitted tail left by an interrupted earlier writer.
  static Result<std::unique_ptr<FrameFileWriter>> OpenForAppend(
      const std::string& path, const FrameFileWriterOptions& options = {});

  ~FrameFileWriter();  // without Commit(): abandons everything written since opening

  const Skeleton& skeleton() const;
  double fps() const;
  FrameLayout layout() const;
  uint64_t frame_count() const;                // committed plus appended so far
  const std::vector<ClipInfo>& clips() const;  // committed plus appended so far

  // Appends one whole clip. `clip.rows` has clip.info.frame_count * layout().stride() floats;
  // clip.info.joint_offsets / end_sites have one entry per joint. InvalidArgument on a size
  // mismatch, a non-finite value, or a clip name already in the archive.
  Status AppendClip(const ClipFrames& clip);
  // The checks AppendClip makes of `clip`'s rows before it writes anything (their count, and
  // every value storable in its column: InvalidArgument), alone; not those of its info.
  Status CheckFrames(const ClipFrames& clip) const;

  // Streaming variant for clips too long to hold: BeginClip (info.frame_count ignored), any
  // number of AppendFrames, EndClip.
  Status BeginClip(const ClipInfo& info);
  Status AppendFrames(const float* rows, size_t frame_count);
  Status EndClip();

  // Flushes the last partial block, writes metadata and footer, syncs, and publishes the new
  // version atomically. After Commit the writer is closed.
  Status Commit();

 private:
  class Impl;
  explicit FrameFileWriter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace motif
