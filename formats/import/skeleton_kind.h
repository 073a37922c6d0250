// Which skeleton a take has, read without its motion: a BVH file's HIERARCHY, an AMC take's ASF.
// The archive import reads it to learn, before the archive exists, whether a folder mixes
// skeleton families (then the archive is on the CMU body and the other families are mapped onto
// it, formats/motion/body_retarget.h).
// Thread-safety: a pure function.
#pragma once

#include <string>

#include "common/status.h"
#include "formats/import/take_importer.h"

namespace motif {

// "cmu31" for the CMU skeleton under either naming; otherwise "custom:" and the joints' names
// and parents in file order (two takes of one rig give the same text). Reads a BVH file only up
// to its MOTION line. The importer's errors for an unreadable file or hierarchy.
Result<std::string> ReadSkeletonKind(const TakeSource& source, const ImportOptions& options);

}  // namespace motif
