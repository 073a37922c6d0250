// An archive opened for a study program, with the pose features of all its frames at the
// skeleton's default joint weights (what the miner's distance uses).
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "common/status.h"
#include "engine/distance/pose_features.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif::testing {

struct StudyArchive {
  std::unique_ptr<FrameFileReader> reader;
  PoseFeatures features;
};

// The reader's, the weights' and the features' errors pass through.
inline Result<StudyArchive> OpenStudyArchive(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<FrameFileReader> reader, FrameFileReader::Open(path));
  MOTIF_ASSIGN_OR_RETURN(std::vector<float> weights, LoadDistanceWeights(reader->skeleton(), ""));
  MOTIF_ASSIGN_OR_RETURN(PoseFeatures features, PoseFeatures::FromArchive(*reader, weights));
  return StudyArchive{std::move(reader), std::move(features)};
}

}  // namespace motif::testing
