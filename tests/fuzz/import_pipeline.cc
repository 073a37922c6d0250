#include "tests/fuzz/import_pipeline.h"

#include <string>

#include "formats/import/first_frame.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/resample.h"
#include "tests/fuzz/fuzz_support.h"

namespace motif::fuzz {
namespace {

void CheckShape(const Take& take, const char* where) {
  if (take.rotations.size() != take.frame_count() * take.joint_count()) {
    Fail(where, std::to_string(take.rotations.size()) + " rotations for " +
                    std::to_string(take.frame_count()) + " frames of " +
                    std::to_string(take.joint_count()) + " joints");
  }
}

}  // namespace

void ImportParsedTake(Take take) {
  CheckShape(take, "parsed take");
  // ImportTake with FirstFramePolicy::kAuto.
  if (CheckFirstFrame(take).discontinuous && take.frame_count() >= 2) DropFirstFrame(&take);
  CanonicalizeSkeleton(&take);
  CheckShape(take, "canonical take");
  if (take.frame_count() == 0) return;  // the archive import rejects an empty take here
  // ImportIntoArchive: resampled to the archive's rate, then rows.
  const Take resampled = ResampleTake(take, kArchiveFps);
  CheckShape(resampled, "resampled take");
  const ClipFrames clip = TakeToClipFrames(resampled);
  const FrameLayout layout{static_cast<uint32_t>(resampled.joint_count())};
  if (clip.rows.size() != resampled.frame_count() * layout.stride()) {
    Fail("clip rows", std::to_string(clip.rows.size()) + " floats for " +
                          std::to_string(resampled.frame_count()) + " frames");
  }
}

}  // namespace motif::fuzz
