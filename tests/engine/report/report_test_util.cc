#include "tests/engine/report/report_test_util.h"

#include <algorithm>
#include <map>

#include "formats/frame_file/frame_file_writer.h"

namespace motif::testing {

Result<SyntheticMotifs> MakeSyntheticMotifs(const std::string& archive_path,
                                            const SynthOptions& options,
                                            const std::string& first_clip_name) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<MotionSynthesizer> synthesizer,
                         MotionSynthesizer::Create(options));
  MOTIF_ASSIGN_OR_RETURN(
      std::unique_ptr<FrameFileWriter> writer,
      FrameFileWriter::Create(archive_path, synthesizer->skeleton(), options.fps));
  std::string renamed_from;
  bool first = true;
  MOTIF_RETURN_IF_ERROR(synthesizer->Run([&](const ClipFrames& clip) {
    if (!first || first_clip_name.empty()) {
      first = false;
      return writer->AppendClip(clip);
    }
    first = false;
    ClipFrames copy = clip;
    renamed_from = clip.info.name;
    copy.info.name = first_clip_name;
    return writer->AppendClip(copy);
  }));
  SyntheticMotifs result;
  result.archive_path = archive_path;
  result.truth = synthesizer->truth();
  for (PlantedInstance& instance : result.truth) {
    if (!renamed_from.empty() && instance.clip == renamed_from) instance.clip = first_clip_name;
  }
  const std::vector<ClipInfo> clips = writer->clips();
  const uint64_t frames = writer->frame_count();
  MOTIF_RETURN_IF_ERROR(writer->Commit());

  MotifsDocument& document = result.document;
  document.archive = archive_path;
  document.frames = frames;
  std::map<std::string, uint64_t> first_frames;
  for (const ClipInfo& clip : clips) {
    document.clips.push_back(
        {clip.name, clip.source_path, clip.frame_count, clip.fps, clip.first_frame});
    first_frames[clip.name] = clip.first_frame;
  }
  document.params = {1.0, 64, 4, 60, 0, 1};
  std::map<uint32_t, std::vector<MotifsJsonInstance>> by_motif;
  for (const PlantedInstance& planted : result.truth) {
    by_motif[planted.motif].push_back(
        {planted.clip, planted.start, planted.end, first_frames[planted.clip] + planted.start});
  }
  for (auto& [motif_id, instances] : by_motif) {
    std::sort(
        instances.begin(), instances.end(),
        [](const MotifsJsonInstance& a, const MotifsJsonInstance& b) { return a.frame < b.frame; });
    document.motifs.push_back({motif_id, instances});
  }
  return result;
}

}  // namespace motif::testing
