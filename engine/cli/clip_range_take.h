// Reading frames [start, end) of one clip of an archive back as a Take (world root trajectory,
// full root rotations, the clip's own bone lengths), ready for WriteBvh: what `motifmine export`
// and `motifmine export-motif` write.
// Thread-safety: pure functions (the reader's const methods are thread-safe).
#pragma once

#include <cstdint>
#include <string>

#include <boost/program_options.hpp>

#include "common/status.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/motion/take.h"

namespace motif::cli {

// Frames [start, end) of `take` (start < end <= take.frame_count()).
Take SliceTake(const Take& take, size_t start, size_t end);

// Frames [start, end) of `clip` (a clip of `reader`), within the clip. The root trajectory is
// integrated from the clip's first frame, so frames [0, end) are read. InvalidArgument if the
// range is empty or outside the clip; Corruption if a block does not decode.
Result<Take> ReadClipRangeAsTake(const FrameFileReader& reader, const ClipInfo& clip,
                                 uint64_t start, uint64_t end);

// The --names option of export and export-motif: "source" (the default: the joints keep the
// names of the file the clip was imported from, where the import renamed them) or "canonical"
// (the archive's names).
void AddJointNamesOption(boost::program_options::options_description* options);
// Checks the option's value; false after printing a usage error naming the flag (exit 2).
bool CheckJointNamesOption(const std::string& command, const std::string& usage,
                           const boost::program_options::variables_map& vm);
// Renames `take`'s joints to the source's names when the option says so and the clip has them.
void ApplyJointNamesOption(const boost::program_options::variables_map& vm, Take* take);

}  // namespace motif::cli
