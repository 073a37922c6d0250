// What the commands that work on a mining result share (`motifmine export-motif`, `motifmine
// report`): DIR/motifs.json read, its archive opened (the document's "archive" field unless
// overridden) and checked to be the archive the motifs were mined from.
// Thread-safety: one thread at a time.
#pragma once

#include <memory>
#include <string>

#include "common/status.h"
#include "engine/cluster/motifs_json.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif::cli {

struct MinedMotifs {
  std::string dir;          // as given
  std::string motifs_path;  // DIR/motifs.json
  MotifsDocument document;
  std::unique_ptr<FrameFileReader> archive;
};

// `dir` is the output folder of `motifmine cluster` (or a motifs.json file itself);
// `archive_path` overrides the document's archive when not empty. NotFound: no motifs.json, no
// archive (messages say how to fix it); InvalidArgument / NotSupported: a malformed
// motifs.json, or one mined from another archive (CheckMotifsMatchArchive); the archive's own
// Open errors.
Result<MinedMotifs> OpenMinedMotifs(const std::string& dir, const std::string& archive_path);

}  // namespace motif::cli
