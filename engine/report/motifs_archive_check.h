// Whether a motifs.json (engine/cluster/motifs_json.h) belongs to an archive: the report and the
// motif export read instance frames from the archive, and motifs mined from another archive, or
// from an earlier version of this one, would point at the wrong motion. motifs.json records no
// archive identity, so the check is structural: the same total frame count, and every clip the
// document lists present in the archive with the same frame count and first global frame.
// Thread-safety: a pure function.
#pragma once

#include "common/status.h"
#include "engine/cluster/motifs_json.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

// OK if `document` matches `reader`'s archive, InvalidArgument naming the first difference
// otherwise (the message names `motifs_path` and the archive's path). Also checks that every
// instance lies inside its clip.
Status CheckMotifsMatchArchive(const MotifsDocument& document, const std::string& motifs_path,
                               const FrameFileReader& reader);

// The archive clip named `name`, or nullptr.
const ClipInfo* FindClip(const FrameFileReader& reader, const std::string& name);

}  // namespace motif
