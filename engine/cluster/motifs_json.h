// motifs.json: the mined motifs, the contract other tools read (docs/guide.md, section cluster).
//
//   {"version": 2, "archive": "...", "frames": N,
//    "clips": [{"name": "05_01", "source": "...", "frames": 1234, "fps": 120.0,
//               "first_frame": 0}, ...],
//    "params": {"eps": ..., "kmax": ..., "branch": ..., "min_length": ..., "groups": ...,
//               "seed": ...},
//    "motifs": [{"id": 0, "instances": [{"clip": "05_01", "start": 100, "end": 260}, ...]}, ...]}
//
// start/end are 0-based frames within the clip, end exclusive; clip names are the clips' names
// (source file stems). Motifs are listed most important first (id = rank); instances by
// position. "groups" is the number asked for, or "auto". "min_length" is the grower's lambda in
// frames (as in the paths file; "min_length_seconds" gives it at the archive's rate).
// "similarity" ("warped" or "shared"), "pause_speed" and "pause_seconds" say how the instances
// were weighed and trimmed (mine's options of those names); files written before them lack them.
// Fields beyond the contract: per motif "instance_count", "mean_length" (frames),
// "mean_seconds", "score" (instance count × mean length, in frames) and "representative" (the
// index of its medoid instance); per instance "frame" (its global first frame), "length",
// "file_first_frame" and "file_last_frame" (FileFrameOf its first and last frame) and
// "distance" (to the representative); per clip "source_fps"; at the top "summary" {"motifs",
// "instances", "covered_frames"}; and "archive_version" {"generation", "committed_bytes",
// "identity" (16 hex digits)}: the archive version (commit) mined, so that a reader opens that
// version (FrameFileReader::OpenCommit) even after later takes were appended to the archive.
// Readers must ignore fields they do not know; the version changes only if a contract field
// changes meaning. Version 2: "archive" is relative to the folder holding motifs.json (absolute
// when the run was given an absolute path), so the file works from any directory; in version 1
// it was the path as given to the run, relative to where it ran. docs/formats/motifs_json.md
// specifies it.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/cluster/motif_clusterer.h"
#include "formats/motion/pose_frames.h"

namespace motif {

struct MotifsJsonClip {
  std::string name;
  std::string source;
  uint64_t frames = 0;
  double fps = 0;
  uint64_t first_frame = 0;
  // The source file's frame of the clip's frame 0 (ClipInfo::source_first_frame); 0 when the
  // document does not say (written before it had the field).
  uint64_t source_first_frame = 0;
  // The source file's rate (ClipInfo::source_fps); 0 when the document does not say: the same
  // as `fps`.
  double source_fps = 0;
  bool operator==(const MotifsJsonClip&) const = default;
};

// The source file's frame of clip frame `clip_frame`: source_first_frame +
// round(clip_frame × source_fps / fps), halves up (source_first_frame + clip_frame when the rate
// is not resampled or not known). What "file_first_frame" / "file_last_frame" hold.
uint64_t FileFrameOf(const MotifsJsonClip& clip, uint64_t clip_frame);

struct MotifsJsonParams {
  double eps = 0;
  uint32_t kmax = 0;
  uint32_t branch = 0;
  uint64_t min_length = 0;  // lambda, frames
  uint32_t groups = 0;      // 0: "auto"
  uint64_t seed = 0;
  // How the motifs were clustered (optional in files: older ones lack them).
  std::string similarity = "warped";  // "warped" or "shared"
  double pause_speed = 0;             // degrees per second; 0: instances not trimmed
  double pause_seconds = 0;
  bool operator==(const MotifsJsonParams&) const = default;
};

struct MotifsJsonInstance {
  std::string clip;
  uint64_t start = 0;  // within the clip
  uint64_t end = 0;    // exclusive
  uint64_t frame = 0;  // global first frame (extra field; the reader computes it from the clips
                       // when absent)
  // The warped distance to its motif's representative (motif_representatives.h), in units of
  // the pose distance; absent in files written before it.
  std::optional<double> distance = std::nullopt;
  uint64_t length() const { return end - start; }
  bool operator==(const MotifsJsonInstance&) const = default;
};

struct MotifsJsonMotif {
  uint32_t id = 0;
  std::vector<MotifsJsonInstance> instances;
  // The index into `instances` of the medoid; when set, every instance has its distance.
  std::optional<uint32_t> representative = std::nullopt;
  bool operator==(const MotifsJsonMotif&) const = default;
};

// The archive version mined (FrameFileSummary): generation and committed length locate it in
// the file, identity checks it. All 0 when unknown (a motifs.json without "archive_version").
struct MotifsArchiveVersion {
  uint64_t generation = 0;
  uint64_t committed_bytes = 0;
  uint64_t identity = 0;
  bool known() const { return generation != 0; }
  bool operator==(const MotifsArchiveVersion&) const = default;
};

struct MotifsDocument {
  // The archive as a path from the current directory (or absolute). WriteMotifsJson stores it
  // relative to the file's folder, ReadMotifsJson resolves it back.
  std::string archive;
  uint64_t frames = 0;
  MotifsArchiveVersion archive_version;
  std::vector<MotifsJsonClip> clips;
  MotifsJsonParams params;
  std::vector<MotifsJsonMotif> motifs;
  uint64_t covered_frames = 0;  // summary (not compared: derived)
  // Set by ParseMotifsJson for a version 2 file: `archive` is still relative to the file's
  // folder (ReadMotifsJson and ResolveArchivePath resolve it).
  bool archive_relative_to_file = false;
  bool operator==(const MotifsDocument& other) const {
    return archive == other.archive && frames == other.frames &&
           archive_version == other.archive_version && clips == other.clips &&
           params == other.params && motifs == other.motifs;
  }
};

// The document of a clustering result over an archive with `clips` (in archive order).
// InvalidArgument if an instance is not inside one clip.
Result<MotifsDocument> MakeMotifsDocument(const ClusterResult& result,
                                          const std::string& archive_path, uint64_t archive_frames,
                                          const std::vector<ClipInfo>& clips,
                                          const MotifsJsonParams& params);

std::string MotifsJsonText(const MotifsDocument& document);
// Written atomically (temporary file, fsync, rename). IOError / ResourceExhausted.
Status WriteMotifsJson(const std::string& path, const MotifsDocument& document);

// InvalidArgument naming the field if the text is not a motifs.json of version 1 or 2 (a missing
// contract field, a wrong type, an instance with end <= start or naming an unknown clip, a
// representative out of range or without distances); NotSupported for another version. The
// fields added later are optional.
Result<MotifsDocument> ParseMotifsJson(const std::string& text, const std::string& name);
Result<MotifsDocument> ReadMotifsJson(const std::string& path);
// For a document parsed from the file at `motifs_path`: its archive path made usable from the
// current directory (a version 2 file's relative path joined to the file's folder).
void ResolveArchivePath(const std::string& motifs_path, MotifsDocument* document);

}  // namespace motif
