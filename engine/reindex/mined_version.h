// MinedVersion: a reader's view of one version of a `motifmine reindex` output: the manifest
// and everything it names, opened together. A reader never sees a half-updated state: the
// manifest is replaced by a rename, and it names only complete files of one version, which no
// later run modifies (a new version is written into a new folder). Once opened, the files stay
// readable for as long as the MinedVersion lives, even after later runs switch versions and
// remove this one (the archive and the trellis are memory-mapped, the paths and the motifs are
// in memory; POSIX keeps an unlinked file's data while it is mapped), and the archive is opened
// at the commit the version was mined from, however many takes were appended since.
// Thread-safety: const access from many threads once opened.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/cluster/motifs_json.h"
#include "engine/reindex/reindex_manifest.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/paths_file/paths_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif {

struct MinedVersion {
  std::string out_dir;
  ReindexManifest manifest;
  std::unique_ptr<FrameFileReader> archive;  // the version mined (manifest.archive)
  std::unique_ptr<TrellisFileReader> trellis;
  std::unique_ptr<PathsFileReader> paths;
  MotifsDocument motifs;
};

// Opens OUTDIR's current version and checks that each file is the one the manifest names
// (size and checksum of motifs.json and paths.mpa, the trellis's and the archive's identities).
// A version removed between reading the manifest and opening its files (only possible when
// two later runs switched meanwhile) makes it read the manifest again, up to `attempts` times.
// NotFound: no manifest (no version yet) or a file gone; Corruption: a file that does not match
// the manifest; the readers' own errors.
Result<MinedVersion> OpenMinedVersion(const std::string& out_dir, int attempts = 3);

// Everything `motifmine verify OUTDIR` checks of the current version: OpenMinedVersion, then
// every block of the trellis and of the archive version, the trellis built over that archive
// version and the paths grown from that trellis, the report's checksum, and that
// OUTDIR/motifs.json is this version's (or, after a run killed between the switch and the
// publication, still the previous one's: a note, not damage). Corruption naming the file.
Status VerifyMinedVersion(const std::string& out_dir, std::vector<std::string>* notes);

}  // namespace motif
