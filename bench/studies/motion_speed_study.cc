// Study: how fast does the body move, frame by frame? Prints "frame<TAB>speed" for every frame
// of an archive (global frames), the speed of engine/cluster/pauses.h: the mean joint rotation
// per second over the skeleton's weighted joints, in degrees per second. Used to see where
// movements start and end and how still a held pose is (docs/design/motif_quality.md, section 8).
//
//   motion_speed_study ARCHIVE.mfs
#include <cstdio>
#include <iostream>
#include <vector>

#include "engine/cluster/pauses.h"
#include "engine/distance/pose_features.h"
#include "formats/frame_file/frame_file_reader.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: motion_speed_study ARCHIVE.mfs\n";
    return 2;
  }
  auto reader = motif::FrameFileReader::Open(argv[1]);
  auto weights = reader.ok() ? motif::LoadDistanceWeights((*reader)->skeleton(), "")
                             : motif::Result<std::vector<float>>(reader.status());
  if (!weights.ok()) {
    std::cerr << weights.status().ToString() << "\n";
    return 1;
  }
  const motif::FrameFileReader& archive = **reader;
  std::vector<float> rows;
  for (const motif::ClipInfo& clip : archive.clips()) {
    if (motif::Status status = archive.ReadFrames(clip.first_frame, clip.frame_count, &rows);
        !status.ok()) {
      std::cerr << status.ToString() << "\n";
      return 1;
    }
    const std::vector<double> speeds = motif::FrameSpeeds(
        rows.data(), clip.frame_count, archive.layout().joint_count, *weights, archive.fps());
    for (size_t idx = 0; idx < speeds.size(); ++idx) {
      std::printf("%llu\t%.3f\n", static_cast<unsigned long long>(clip.first_frame + idx),
                  speeds[idx]);
    }
  }
  return 0;
}
