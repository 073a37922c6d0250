// FrameFileReader: opens a motion archive (.mfs, docs/formats/frame_file.md) by memory-mapping it
// with Boost.Interprocess, validates it from the footer (through the header's commit slots), and
// hands out decoded frames: random access to any frame range, or a FrameStream that walks the
// archive block by block with bounded memory. Every block's checksum is checked when it is
// decoded; Verify() checks all of them.
// Thread-safety: once open, const methods may be called from many threads at once.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/status.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/skeleton.h"

namespace motif {

struct FrameFileSummary {
  uint64_t file_bytes = 0;  // committed length
  uint64_t block_count = 0;
  uint64_t compressed_bytes = 0;  // sum of block sizes
  uint32_t block_frames = 0;      // the writer's nominal block size
  uint64_t generation = 0;        // commits so far (1 after creation)
  uint32_t format_major = 0;
  uint32_t format_minor = 0;
  // Identifies this version of the archive (its metadata checksum: the clip table and block
  // index with their block checksums): results derived from the archive record it, and are
  // rebuilt when it changes (an append, another archive).
  uint64_t identity = 0;
  uint64_t uncommitted_bytes = 0;  // bytes after the committed length (an interrupted append)
  // Non-empty if the newest commit slot did not validate and the previous version was opened
  // instead (Verify() then returns Corruption with this reason).
  std::string fallback_reason;
  // Non-empty if the newest version's commit slot is damaged and it was read from its footer at
  // the end of the file instead (its data validated as usual; Verify() returns Corruption with
  // this reason, and the next commit goes to the other slot).
  std::string damaged_slot_reason;
};

class FrameStream;

// Which version of an archive to open: the newest (the default), or the one committed as
// `generation` with `committed_bytes` bytes. A command that opens its archive more than once
// (each stage of `mine`) pins the version it opened first, so an import appending meanwhile
// changes nothing it reads.
struct FrameFileVersion {
  uint64_t generation = 0;  // 0: the newest
  uint64_t committed_bytes = 0;
  bool newest() const { return generation == 0; }
};

// What Open() does when the newest commit does not validate and it opened the previous version
// (summary().fallback_reason non-empty). Without a handler it returns that version, and the
// caller checks the summary. A program sets one handler, once, before opening archives; the
// motifmine tool's refuses with Corruption unless --allow-older is given, and warns on stderr
// when it is (docs/guide.md, "Damaged archives"). An error the handler returns is Open's result.
using OlderVersionHandler =
    std::function<Status(const std::string& path, const FrameFileSummary& opened)>;
void SetOlderVersionHandler(OlderVersionHandler handler);

class FrameFileReader {
 public:
  // Opens and validates. NotFound: no file. NotSupported: another major version. Corruption:
  // bad magic, a checksum mismatch in the header slots, footer or metadata, an index pointing
  // outside the file. IOError: cannot open or map. Messages name the file and the offset. When
  // only an older version validates, the OlderVersionHandler decides (above).
  static Result<std::unique_ptr<FrameFileReader>> Open(const std::string& path);
  // Opens an earlier version of the archive: the one committed as `generation` with
  // `committed_length` bytes (FrameFileSummary::generation and file_bytes when it was
  // current). Appends never rewrite those bytes, so a result that recorded them (a reindex
  // manifest, motifs.json) reads the frames it was mined from while later takes are appended.
  // Corruption if that version is not in the file (another archive, a truncated file).
  static Result<std::unique_ptr<FrameFileReader>> OpenCommit(const std::string& path,
                                                             uint64_t generation,
                                                             uint64_t committed_length);
  // OpenCommit for a pinned version, Open for FrameFileVersion{} (the newest).
  static Result<std::unique_ptr<FrameFileReader>> OpenVersion(const std::string& path,
                                                              const FrameFileVersion& version);
  ~FrameFileReader();

  const std::string& path() const;
  const Skeleton& skeleton() const;
  double fps() const;
  FrameLayout layout() const;
  uint64_t frame_count() const;
  const std::vector<ClipInfo>& clips() const;
  // Index into clips() of the clip holding global frame `frame_idx` (frame_idx < frame_count()).
  size_t ClipOfFrame(uint64_t frame_idx) const;
  FrameFileSummary summary() const;
  // The version opened, to pin it for the next opens (OpenVersion).
  FrameFileVersion version() const;

  // Decodes frames [first_frame, first_frame + frame_count) into `rows` (resized to
  // frame_count * layout().stride()). InvalidArgument if the range is outside the archive;
  // Corruption if a block fails its checksum or does not decode.
  Status ReadFrames(uint64_t first_frame, uint64_t frame_count, std::vector<float>* rows) const;

  // A stream over frames [first_frame, end_frame) in order, one block at a time (end_frame is
  // clamped to frame_count(); an empty range gives a stream that ends at once). The reader must
  // outlive the stream.
  std::unique_ptr<FrameStream> Stream(uint64_t first_frame = 0,
                                      uint64_t end_frame = UINT64_MAX) const;

  // Checks every block's checksum and that it decodes. `progress(done, total)` is called after
  // each block if given. Corruption naming the first bad block and its offset, the reason
  // the newest commit was passed over (summary().fallback_reason), or the damaged slot of the
  // version opened (summary().damaged_slot_reason).
  Status Verify(const std::function<void(uint64_t, uint64_t)>& progress = nullptr) const;

 private:
  class Impl;
  explicit FrameFileReader(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  friend class FrameStream;
};

// Frames in order, block by block. Holds one decoded block at a time and releases the pages of
// blocks already read, so resident memory does not grow with the archive.
class FrameStream {
 public:
  virtual ~FrameStream() = default;
  // Advances to the next run of frames. Returns false at the end. On OK/true, first_frame(),
  // frame_count() and rows() describe the run (rows: frame_count() * stride floats, valid until
  // the next call).
  virtual Result<bool> Next() = 0;
  virtual uint64_t first_frame() const = 0;
  virtual uint64_t frame_count() const = 0;
  virtual const float* rows() const = 0;
};

}  // namespace motif
