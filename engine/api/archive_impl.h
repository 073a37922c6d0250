// The state behind motifmine::Archive (include/motifmine/archive.h), shared by the files that
// implement it: public_archive.cc (opening, clips, rotations) and public_archive_pose.cc (the
// skeleton, the root, world positions). The reader's const methods are thread-safe.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "formats/frame_file/frame_file_reader.h"
#include "motifmine/archive.h"

namespace motifmine {

class Archive::Impl {
 public:
  std::unique_ptr<motif::FrameFileReader> reader;
  std::vector<Clip> clips;

  // The clip named `clip` in *info. NotFound naming the archive for an unknown clip.
  Status FindClip(const std::string& clip, const motif::ClipInfo** info) const;
  // The same, and frames [start, end) within it: InvalidArgument naming the range otherwise.
  Status FindRange(const std::string& clip, uint64_t start, uint64_t end,
                   const motif::ClipInfo** info) const;
};

}  // namespace motifmine
