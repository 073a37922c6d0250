#include "engine/synth/synthetic_archive.h"

#include <memory>

#include "common/file_util.h"
#include "common/writable_file.h"
#include "engine/synth/truth_json_reader.h"
#include "formats/frame_file/frame_file_writer.h"

namespace motif {

Result<uint64_t> WriteSyntheticArchive(const std::string& out, MotionSynthesizer& synthesizer,
                                       const SynthOptions& options, uint32_t block_frames,
                                       const std::function<void(uint64_t, uint64_t)>& progress) {
  const std::string staging = TemporaryPathFor(out);
  FrameFileWriterOptions writer_options;
  writer_options.block_frames = block_frames;
  MOTIF_ASSIGN_OR_RETURN(
      std::unique_ptr<FrameFileWriter> writer,
      FrameFileWriter::Create(staging, synthesizer.skeleton(), options.fps, writer_options));
  if (progress) progress(0, options.frames);
  uint64_t frames_done = 0;
  Status status = synthesizer.Run([&](const ClipFrames& clip) {
    MOTIF_RETURN_IF_ERROR(writer->AppendClip(clip));
    frames_done += clip.info.frame_count;
    if (progress) progress(frames_done, options.frames);
    return Status::Ok();
  });
  if (status.ok()) status = writer->Commit();
  writer.reset();
  if (status.ok()) status = PosixFileSystem()->Rename(staging, out);
  if (!status.ok()) {
    (void)PosixFileSystem()->Remove(staging);  // best effort: the error that matters is `status`
    return status;
  }
  MOTIF_RETURN_IF_ERROR(
      WriteTruthJson(TruthPathFor(out), out, frames_done, options, synthesizer.truth()));
  return frames_done;
}

}  // namespace motif
