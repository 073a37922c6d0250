// A folder `motifmine mine --out DIR` wrote, given where a command wants an archive: the
// commands that read an archive (graph, words, search, segment, classify, info, export) take
// DIR for the archive mined there, so a user does not have to know the
// folder's layout; and `graph` uses the trellis mine left there instead of building another.
// Thread-safety: functions of the file system only.
#pragma once

#include <string>

#include "formats/frame_file/frame_file_reader.h"

namespace motif {

// The archive a mine output folder mined: the one its motifs.json names (relative to DIR
// unless absolute), else DIR/archive.mfs. Empty when `path` is not such a folder.
std::string ArchiveOfMinedFolder(const std::string& path);

// Where ParseCommand leaves the folder when it replaced ARCHIVE by the archive mined there.
inline constexpr char kMinedFolderKey[] = "mined-folder";

// Whether a command named `command` reads the archive its ARCHIVE argument names (and so
// takes a mine output folder for it).
bool ReadsArchiveArgument(const std::string& command);

// The trellis of the mine output folder `folder` (DIR/trellis.mtr beside DIR/mine_state.json)
// when it is a finished trellis of exactly the version `archive` reads; empty otherwise (not
// such a folder, or the archive grew after the run).
std::string MinedTrellisOf(const std::string& folder, const FrameFileReader& archive);

}  // namespace motif
