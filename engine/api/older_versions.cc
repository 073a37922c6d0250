// The public API's older-version policy (motifmine::AllowOlderVersions, include/motifmine/
// archive.h): an archive whose newest commit is damaged is refused with Corruption, as the tool
// refuses it without --allow-older, unless the calling thread allowed older versions. Without
// it the reader would hand back the previous version and a caller would never know.
#include <string>

#include "formats/frame_file/frame_file_reader.h"
#include "motifmine/archive.h"

namespace motifmine {
namespace {

thread_local bool older_versions_allowed = false;

motif::Status RefuseUnlessAllowed(const std::string& path, const motif::FrameFileSummary& opened) {
  if (older_versions_allowed) return motif::Status::Ok();
  return motif::Status::Corruption(
      opened.fallback_reason + "; not reading the previous version (generation " +
      std::to_string(opened.generation) + ", " + std::to_string(opened.file_bytes) +
      " bytes) in its place: run `motifmine verify " + path +
      "`, or allow older versions (motifmine::AllowOlderVersions; Python: allow_older=True)");
}

// Installed when libmotifmine is loaded, before any of its calls can open an archive.
[[maybe_unused]] const bool policy_installed = [] {
  motif::SetOlderVersionHandler(RefuseUnlessAllowed);
  return true;
}();

}  // namespace

bool AllowOlderVersions(bool allow) {
  const bool before = older_versions_allowed;
  older_versions_allowed = allow;
  return before;
}

}  // namespace motifmine
