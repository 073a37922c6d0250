// motifmine verify ARCHIVE: every checksum, every block decoded.
#include <cstdio>

#include "engine/cli/cli_common.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif::cli {

namespace po = boost::program_options;

int RunVerify(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "verify";
  spec.usage = "motifmine verify ARCHIVE";
  spec.summary =
      "Checks an archive: its header, footer and metadata checksums, then every block's checksum\n"
      "and that it decodes. Exits 0 when all is well, 12 (corruption) naming the first damage.";
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const std::string path = vm["archive"].as<std::string>();
  Result<std::unique_ptr<FrameFileReader>> opened = FrameFileReader::Open(path);
  if (!opened.ok()) return ReportError("verify", opened.status());
  const FrameFileReader& reader = **opened;
  ProgressReporter progress(ProgressModeFrom(vm));
  progress.BeginStage("verify", reader.summary().block_count, "blocks");
  Status status = reader.Verify([&](uint64_t done, uint64_t) { progress.Update(done); });
  progress.EndStage();
  if (!status.ok()) return ReportError("verify", status);
  std::printf("OK: %s: %s blocks, %s clips, %s frames verified\n", path.c_str(),
              WithCommas(reader.summary().block_count).c_str(),
              WithCommas(reader.clips().size()).c_str(), WithCommas(reader.frame_count()).c_str());
  return kExitOk;
}

}  // namespace motif::cli
