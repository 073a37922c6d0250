// motifmine inspect-trellis ARCHIVE --column T: one column of the trellis, readable.
#include <cstdio>

#include "engine/cli/cli_common.h"
#include "engine/trellis/trellis_builder.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"

namespace motif::cli {

namespace po = boost::program_options;

int RunInspectTrellis(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "inspect-trellis";
  spec.usage = "motifmine inspect-trellis ARCHIVE --column T [--trellis PATH]";
  spec.summary =
      "Prints the trellis's parameters and column T: each neighbour's global frame, its "
      "clip and\nframe within the clip, and its pose distance.";
  spec.options.add_options()("column", po::value<uint64_t>()->required(),
                             "global frame index of the column")(
      "trellis", po::value<std::string>()->default_value(""), "default: ARCHIVE.mtr");
  spec.positional = {{"archive", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const std::string archive = vm["archive"].as<std::string>();
  std::string path = vm["trellis"].as<std::string>();
  if (path.empty()) path = DefaultTrellisPath(archive);
  Result<std::unique_ptr<FrameFileReader>> reader = FrameFileReader::Open(archive);
  if (!reader.ok()) return ReportError("inspect-trellis", reader.status());
  Result<std::unique_ptr<TrellisFileReader>> trellis = TrellisFileReader::Open(path);
  if (!trellis.ok()) return ReportError("inspect-trellis", trellis.status());
  const uint64_t column = vm["column"].as<uint64_t>();
  if (column >= (*trellis)->column_count()) {
    return ReportError(
        "inspect-trellis",
        Status::InvalidArgument("column " + std::to_string(column) + " is outside the trellis's " +
                                std::to_string((*trellis)->column_count()) + " columns"));
  }
  const TrellisParams& params = (*trellis)->params();
  if (params.archive_identity != (*reader)->summary().identity) {
    std::fprintf(stderr, "warning: %s was built from another version of %s\n", path.c_str(),
                 archive.c_str());
  }
  std::vector<std::vector<Neighbour>> columns;
  Status status = (*trellis)->ReadColumns(column, 1, &columns);
  if (!status.ok()) return ReportError("inspect-trellis", status);
  const auto& clips = (*reader)->clips();
  auto describe = [&](uint64_t frame) {
    const ClipInfo& clip = clips[(*reader)->ClipOfFrame(frame)];
    return clip.name + ":" + std::to_string(frame - clip.first_frame);
  };
  std::printf("%s: eps %.4f, k_max %u, exclusion %u, %s\n", path.c_str(), params.eps, params.k_max,
              params.exclusion_frames, params.search_params.c_str());
  std::printf("column %llu (%s): %zu neighbours\n", static_cast<unsigned long long>(column),
              describe(column).c_str(), columns[0].size());
  std::printf("  %12s  %-28s %10s\n", "frame", "clip:frame", "distance");
  for (const Neighbour& neighbour : columns[0]) {
    std::printf("  %12u  %-28s %10.4f\n", neighbour.frame, describe(neighbour.frame).c_str(),
                neighbour.distance);
  }
  return kExitOk;
}

}  // namespace motif::cli
