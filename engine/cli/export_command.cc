// motifmine export ARCHIVE --clip NAME [--start S --end E] --out FILE.bvh
#include <cstdio>

#include "engine/cli/cli_common.h"
#include "engine/cli/clip_range_take.h"
#include "formats/export/bvh_writer.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif::cli {

namespace po = boost::program_options;

int RunExport(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "export";
  spec.usage =
      "motifmine export ARCHIVE --clip NAME [--start S] [--end E] --out FILE.bvh "
      "[--names source|canonical]";
  spec.summary =
      "Writes a clip, or frames [S, E) of it (0-based, E exclusive), as a BVH file that opens in\n"
      "Blender and other BVH viewers, with the clip's own bone lengths and its root trajectory.";
  spec.options.add_options()("clip", po::value<std::string>()->required(),
                             "clip name (see motifmine info)")(
      "start", po::value<uint64_t>()->default_value(0), "first frame, 0-based")(
      "end", po::value<uint64_t>(), "end frame, exclusive (default: the clip's end)")(
      "out", po::value<std::string>()->required(), "the BVH file to write");
  AddJointNamesOption(&spec.options);
  spec.positional = {{"archive", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  if (!CheckJointNamesOption("export", spec.usage, vm)) return kExitUsage;
  const std::string path = vm["archive"].as<std::string>();
  Result<std::unique_ptr<FrameFileReader>> opened = FrameFileReader::Open(path);
  if (!opened.ok()) return ReportError("export", opened.status());
  const FrameFileReader& reader = **opened;
  const std::string name = vm["clip"].as<std::string>();
  const ClipInfo* clip = nullptr;
  for (const ClipInfo& candidate : reader.clips()) {
    if (candidate.name == name) clip = &candidate;
  }
  if (clip == nullptr) {
    return ReportError(
        "export", Status::NotFound(path + ": no clip named '" + name + "' (motifmine info " + path +
                                   " --clips 0 lists them)"));
  }
  const uint64_t start = vm["start"].as<uint64_t>();
  const uint64_t end = vm.count("end") ? vm["end"].as<uint64_t>() : clip->frame_count;
  Result<Take> take = ReadClipRangeAsTake(reader, *clip, start, end);
  if (!take.ok()) return ReportError("export", take.status());
  ApplyJointNamesOption(vm, &*take);
  const std::string out = vm["out"].as<std::string>();
  if (Status status = WriteBvh(*take, out); !status.ok()) return ReportError("export", status);
  std::printf("wrote %s: clip %s frames [%llu, %llu), %llu frames at %g fps\n", out.c_str(),
              name.c_str(), static_cast<unsigned long long>(start),
              static_cast<unsigned long long>(end), static_cast<unsigned long long>(end - start),
              take->fps);
  return kExitOk;
}

}  // namespace motif::cli
