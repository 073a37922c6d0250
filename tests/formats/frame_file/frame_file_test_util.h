// Helpers shared by the frame file tests: seeded smooth synthetic clips (unit quaternions with
// continuous signs, a slowly moving root), skeletons, whole-archive reads, byte-level file
// helpers and a FileSystem that records the steps a writer takes.
// Thread-safety: plain functions; RecordingFileSystem is used by one thread.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/writable_file.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/skeleton.h"

#include "tests/testing/byte_files.h"

namespace motif::testing {

// prefix + index ("c" + std::to_string(i) trips GCC 12's -Wrestrict false positive).
std::string Numbered(const std::string& prefix, uint64_t index);

// A chain skeleton of `joint_count` joints named "j0", "j1", ... (family "custom").
Skeleton MakeSkeleton(uint32_t joint_count);

// A clip of smooth motion: each joint turns about a slowly drifting axis by a sinusoidal angle
// with a little noise; the root height, velocity and heading vary smoothly. Deterministic in
// `seed`. info.first_frame is 0 (the writer assigns it).
ClipFrames MakeClip(const std::string& name, uint32_t joint_count, uint64_t frame_count,
                    uint32_t seed, double fps = 120.0);

// Writes `clips` to a new archive at `path` and commits; fails the test on error.
void WriteArchive(const std::string& path, const Skeleton& skeleton,
                  const std::vector<ClipFrames>& clips, const FrameFileWriterOptions& options = {},
                  double fps = 120.0);
// Appends `clips` to the archive at `path` and commits; fails the test on error.
void AppendToArchive(const std::string& path, const std::vector<ClipFrames>& clips,
                     const FrameFileWriterOptions& options = {});

// Everything an archive holds, decoded.
struct ArchiveContents {
  Skeleton skeleton;
  double fps = 0;
  std::vector<ClipInfo> clips;
  std::vector<float> rows;
};
// Opens and decodes all frames; the status of the first failure otherwise.
Result<ArchiveContents> ReadContents(const std::string& path);

// Field-by-field equality, as gtest assertions (float rows compared bit for bit).
void ExpectSameClipInfo(const ClipInfo& expected, const ClipInfo& actual);
void ExpectSameSkeleton(const Skeleton& expected, const Skeleton& actual);
void ExpectSameContents(const ArchiveContents& expected, const ArchiveContents& actual);
bool SameBits(const std::vector<float>& a, const std::vector<float>& b);

// Checks decoded rows against the rows written, within the default quantisation bounds:
// rotation angle <= 4 * quaternion_step, other values <= step / 2 (plus float32 rounding).
void ExpectWithinQuantisationBound(const std::vector<float>& written,
                                   const std::vector<float>& decoded, uint32_t joint_count,
                                   const FrameFileWriterOptions& options = {});

// Names of the files in `dir`, sorted.
std::vector<std::string> ListDir(const std::string& dir);

// Forwards to `base` and logs every mutating step as FaultInjectingFileSystem counts them:
// "open <path>", "write <offset> <size>", "fsync", "truncate <size>", "rename", "fsync
// directory", "remove".
class RecordingFileSystem final : public FileSystem {
 public:
  explicit RecordingFileSystem(FileSystem* base = PosixFileSystem()) : base_(base) {}
  Result<std::unique_ptr<WritableFile>> OpenWritable(const std::string& path,
                                                     OpenMode mode) override;
  Status Rename(const std::string& from, const std::string& to) override;
  Status SyncParentDir(const std::string& path) override;
  Status Remove(const std::string& path) override;

  const std::vector<std::string>& steps() const { return steps_; }
  void Log(std::string step) { steps_.push_back(std::move(step)); }

 private:
  FileSystem* base_;
  std::vector<std::string> steps_;
};

}  // namespace motif::testing
