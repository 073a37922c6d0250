// motifmine info ARCHIVE [--json]: what an archive holds.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "engine/cli/cli_common.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

void AddInfoOptions(CommandSpec& spec) {
  spec.name = "info";
  spec.usage = "motifmine info ARCHIVE [--json] [--clips N]";
  spec.summary = "Describes an archive: frame rate, skeleton, clips and frames, size on disk.";
  spec.options.add_options()("json", "print everything as one JSON object (every clip included)")(
      "clips", po::value<size_t>()->default_value(20), "clips listed in the text output (0: all)");
  spec.positional = {{"archive", 1}};
}

struct InfoCommandOptions {
  std::string path;
  bool json = false;
  size_t clip_limit = 20;  // clips listed in the text (0: all)
};

InfoCommandOptions ReadInfoOptions(const po::variables_map& vm) {
  InfoCommandOptions options;
  options.path = vm["archive"].as<std::string>();
  options.json = vm.count("json") > 0;
  options.clip_limit = vm["clips"].as<size_t>();
  return options;
}

uint64_t RawFloat32Bytes(const FrameFileReader& reader) {
  return reader.frame_count() * reader.layout().stride() * sizeof(float);
}

nlohmann::json InfoSkeletonJson(const Skeleton& skeleton) {
  nlohmann::json joints = nlohmann::json::array();
  for (const Joint& joint : skeleton.joints()) {
    joints.push_back({{"name", joint.name}, {"parent", joint.parent}, {"weight", joint.weight}});
  }
  return {{"family", skeleton.family()}, {"joints", joints}};
}

nlohmann::json InfoClipsJson(const std::vector<ClipInfo>& clip_infos) {
  nlohmann::json clips = nlohmann::json::array();
  for (const ClipInfo& clip : clip_infos) {
    clips.push_back({{"name", clip.name},
                     {"source", clip.source_path},
                     {"frames", clip.frame_count},
                     {"fps", clip.fps},
                     {"source_fps", clip.source_fps},
                     {"source_first_frame", clip.source_first_frame},
                     {"first_frame", clip.first_frame}});
    if (!clip.source_joint_names.empty()) {
      clips.back()["source_joint_names"] = clip.source_joint_names;
    }
    if (!clip.description.empty()) clips.back()["description"] = clip.description;
  }
  return clips;
}

// Everything, every clip included, as one JSON object.
nlohmann::json InfoJson(const std::string& path, const FrameFileReader& reader) {
  const FrameFileSummary summary = reader.summary();
  nlohmann::json out;
  out["archive"] = path;
  out["format_version"] =
      std::to_string(summary.format_major) + "." + std::to_string(summary.format_minor);
  out["generation"] = summary.generation;
  out["fps"] = reader.fps();
  out["frames"] = reader.frame_count();
  out["seconds"] = reader.frame_count() / reader.fps();
  out["file_bytes"] = summary.file_bytes;
  out["compressed_bytes"] = summary.compressed_bytes;
  out["raw_float32_bytes"] = RawFloat32Bytes(reader);
  out["blocks"] = summary.block_count;
  out["block_frames"] = summary.block_frames;
  out["uncommitted_bytes"] = summary.uncommitted_bytes;
  out["fallback_reason"] = summary.fallback_reason;
  out["damaged_slot_reason"] = summary.damaged_slot_reason;
  out["skeleton"] = InfoSkeletonJson(reader.skeleton());
  out["clips"] = InfoClipsJson(reader.clips());
  return out;
}

// The archive's header lines: format, frames, clips, skeleton, size and compression.
void PrintInfoOverview(const std::string& path, const FrameFileReader& reader,
                       const FrameFileSummary& summary) {
  const Skeleton& skeleton = reader.skeleton();
  const uint64_t raw_bytes = RawFloat32Bytes(reader);
  std::printf("archive      %s (format %u.%u, generation %llu)\n", path.c_str(),
              summary.format_major, summary.format_minor,
              static_cast<unsigned long long>(summary.generation));
  std::printf("frames       %s at %g fps (%.1f s)\n", WithCommas(reader.frame_count()).c_str(),
              reader.fps(), reader.frame_count() / reader.fps());
  std::printf("clips        %s\n", WithCommas(reader.clips().size()).c_str());
  size_t weighted = 0;
  for (const Joint& joint : skeleton.joints()) weighted += joint.weight > 0;
  std::printf("skeleton     %s, %zu joints (%zu weighted in the pose distance)\n",
              skeleton.family().c_str(), skeleton.joint_count(), weighted);
  std::printf("size         %s bytes on disk, %s of up to %u frames\n",
              WithCommas(summary.file_bytes).c_str(), CountOf(summary.block_count, "block").c_str(),
              summary.block_frames);
  if (summary.compressed_bytes > 0) {
    std::printf("compression  %.2fx against raw float32 (%s bytes)\n",
                static_cast<double>(raw_bytes) / summary.compressed_bytes,
                WithCommas(raw_bytes).c_str());
  }
}

// Bytes of an interrupted import, a damaged commit slot, a commit that did not validate.
void PrintInfoWarnings(const FrameFileSummary& summary) {
  if (summary.uncommitted_bytes > 0) {
    std::printf(
        "note         %s bytes after the last commit (an interrupted import); the next "
        "import discards them\n",
        WithCommas(summary.uncommitted_bytes).c_str());
  }
  if (!summary.damaged_slot_reason.empty()) {
    std::printf("WARNING      %s; its data is whole. Run motifmine verify.\n",
                summary.damaged_slot_reason.c_str());
  }
  if (!summary.fallback_reason.empty()) {
    std::printf(
        "WARNING      the newest commit did not validate (%s); showing the previous "
        "version. Run motifmine verify.\n",
        summary.fallback_reason.c_str());
  }
}

// The first `limit` clips (0: all), then how the frames count.
void PrintInfoClips(const std::vector<ClipInfo>& clips, size_t limit) {
  // "file frame": the source file's frame (0-based, in the file's order) of the clip's frame 0;
  // clip frame k is file frame F + k (times source fps / fps for a resampled take).
  std::printf("\n  %-24s %10s %12s %8s %10s  %s\n", "clip", "frames", "first frame", "fps",
              "file frame", "source");
  for (size_t clip_idx = 0; clip_idx < clips.size(); ++clip_idx) {
    if (limit > 0 && clip_idx >= limit) {
      std::printf("  ... %zu more (use --clips 0 to list all)\n", clips.size() - clip_idx);
      break;
    }
    const ClipInfo& clip = clips[clip_idx];
    std::printf("  %-24s %10s %12s %8g %10s  %s\n", clip.name.c_str(),
                WithCommas(clip.frame_count).c_str(), WithCommas(clip.first_frame).c_str(),
                clip.fps, WithCommas(clip.source_first_frame).c_str(),
                (clip.source_path + (clip.description.empty() ? "" : " (" + clip.description + ")"))
                    .c_str());
  }
  std::printf(
      "\n  frames are 0-based; clip frame k is frame (file frame + k) of its source file, counted "
      "from 0 in the file's order (an AMC labels it one more); a take resampled from another "
      "rate: file frame + k x source fps / fps\n");
}

}  // namespace

int RunInfo(const std::vector<std::string>& args) {
  CommandSpec spec;
  AddInfoOptions(spec);
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const InfoCommandOptions options = ReadInfoOptions(vm);
  Result<std::unique_ptr<FrameFileReader>> opened = FrameFileReader::Open(options.path);
  if (!opened.ok()) return ReportError("info", opened.status());
  const FrameFileReader& reader = **opened;
  if (options.json) {
    std::printf("%s\n", InfoJson(options.path, reader).dump(2).c_str());
    return kExitOk;
  }
  const FrameFileSummary summary = reader.summary();
  PrintInfoOverview(options.path, reader, summary);
  PrintInfoWarnings(summary);
  PrintInfoClips(reader.clips(), options.clip_limit);
  return kExitOk;
}

}  // namespace motif::cli
