// motifmine export-motif DIR --motif ID --out FOLDER [--archive PATH]: writes every instance of
// one mined motif as a BVH file, FOLDER/motif<ID>_<k>_<clip>_<start>-<end>.bvh.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "engine/cli/cli_common.h"
#include "engine/cli/clip_range_take.h"
#include "engine/cli/mined_motifs.h"
#include "engine/report/motifs_archive_check.h"
#include "formats/export/bvh_writer.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

// Clip names are file stems, but may hold characters some file systems or shells dislike.
std::string FileNamePart(const std::string& text) {
  std::string part;
  for (char c : text) {
    const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '-' || c == '.' || c == '~';
    part += safe ? c : '_';
  }
  return part;
}

std::string MotifIdRange(const MotifsDocument& document) {
  if (document.motifs.empty()) return "it holds no motifs";
  uint32_t low = document.motifs.front().id;
  uint32_t high = low;
  for (const MotifsJsonMotif& motif : document.motifs) {
    low = std::min(low, motif.id);
    high = std::max(high, motif.id);
  }
  return "its motifs are " + std::to_string(low) + " to " + std::to_string(high);
}

}  // namespace

int RunExportMotif(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "export-motif";
  spec.usage =
      "motifmine export-motif DIR --motif ID --out FOLDER [--archive PATH] "
      "[--names source|canonical]";
  spec.summary =
      "Writes every instance of motif ID of DIR/motifs.json (the output of `motifmine cluster`)\n"
      "as a BVH file FOLDER/motif<ID>_<k>_<clip>_<start>-<end>.bvh (k counts the instances from\n"
      "0 in motifs.json order; start and end are the instance's frames in its clip, end\n"
      "excluded), with the clip's bone lengths and root trajectory. The frames come from the\n"
      "archive named in motifs.json, or --archive if it has moved.";
  spec.options.add_options()("motif", po::value<uint32_t>()->required(),
                             "the motif id (see motifs.json or the report)")(
      "out", po::value<std::string>()->required(), "folder for the BVH files (created if missing)")(
      "archive", po::value<std::string>()->default_value(""),
      "the archive (default: the one named in motifs.json)");
  AddJointNamesOption(&spec.options);
  spec.positional = {{"dir", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  if (!CheckJointNamesOption("export-motif", spec.usage, vm)) return kExitUsage;
  Result<MinedMotifs> mined =
      OpenMinedMotifs(vm["dir"].as<std::string>(), vm["archive"].as<std::string>());
  if (!mined.ok()) return ReportError("export-motif", mined.status());
  const MotifsDocument& document = mined->document;
  const FrameFileReader& reader = *mined->archive;
  const uint32_t motif_id = vm["motif"].as<uint32_t>();
  const MotifsJsonMotif* motif = nullptr;
  for (const MotifsJsonMotif& candidate : document.motifs) {
    if (candidate.id == motif_id) motif = &candidate;
  }
  if (motif == nullptr) {
    return ReportError("export-motif",
                       Status::NotFound("no motif " + std::to_string(motif_id) + " in " +
                                        mined->motifs_path + ": " + MotifIdRange(document)));
  }
  const std::string out_dir = vm["out"].as<std::string>();
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) {
    return ReportError("export-motif",
                       Status::IOError("cannot create " + out_dir + ": " + error.message()));
  }
  // Each instance is read like `motifmine export` reads a range: from its clip's first frame,
  // because the root trajectory is integrated from there.
  for (size_t instance_idx = 0; instance_idx < motif->instances.size(); ++instance_idx) {
    const MotifsJsonInstance& instance = motif->instances[instance_idx];
    const ClipInfo* clip = FindClip(reader, instance.clip);  // checked by OpenMinedMotifs
    Result<Take> take = ReadClipRangeAsTake(reader, *clip, instance.start, instance.end);
    if (!take.ok()) return ReportError("export-motif", take.status());
    ApplyJointNamesOption(vm, &*take);
    const std::string name = "motif" + std::to_string(motif_id) + "_" +
                             std::to_string(instance_idx) + "_" + FileNamePart(instance.clip) +
                             "_" + std::to_string(instance.start) + "-" +
                             std::to_string(instance.end) + ".bvh";
    const std::string path = (std::filesystem::path(out_dir) / name).string();
    if (Status status = WriteBvh(*take, path); !status.ok()) {
      return ReportError("export-motif", status);
    }
    std::printf("wrote %s: %llu frames (%.2f s)\n", path.c_str(),
                static_cast<unsigned long long>(instance.length()),
                static_cast<double>(instance.length()) / take->fps);
  }
  std::printf("motif %u: %zu instances written to %s\n", motif_id, motif->instances.size(),
              out_dir.c_str());
  return kExitOk;
}

}  // namespace motif::cli
