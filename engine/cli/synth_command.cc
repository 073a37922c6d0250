// motifmine synth OUT.mfs --frames N --motifs M --seed S [--from PATH...]
#include <cstdio>
#include <filesystem>

#include "common/file_util.h"
#include "engine/cli/cli_common.h"
#include "engine/cli/table_options.h"
#include "engine/synth/motion_synthesizer.h"
#include "engine/synth/synthetic_archive.h"
#include "engine/synth/truth_json_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/import/take_importer.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/resample.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

// Imports the real takes to re-sequence, all mapped to the first one's skeleton and at `fps`.
Result<std::vector<Take>> LoadSourceTakes(const std::vector<std::string>& paths, double fps,
                                          ProgressReporter* progress) {
  ImportOptions options;
  MOTIF_ASSIGN_OR_RETURN(std::vector<TakeSource> sources, DiscoverTakes(paths, options));
  if (sources.empty()) return Status::InvalidArgument("--from: no .bvh or .amc takes found");
  std::vector<Take> takes;
  progress->BeginStage("load takes", sources.size(), "takes");
  for (const TakeSource& source : sources) {
    MOTIF_ASSIGN_OR_RETURN(Take take, ImportTake(source, options));
    if (!takes.empty()) {
      Status status = ConformToSkeleton(takes.front().skeleton, &take);
      if (!status.ok()) {
        progress->Note("skipped " + source.path + ": " + status.message());
        continue;
      }
    }
    takes.push_back(ResampleTake(take, fps));
    progress->Update(takes.size());
  }
  progress->EndStage();
  return takes;
}

void AddSynthOptions(CommandSpec& spec) {
  spec.name = "synth";
  spec.usage = "motifmine synth OUT.mfs --frames N --motifs M --seed S [--from PATH...] [options]";
  spec.summary =
      "Writes a synthetic archive of plausible skeletal motion (canonical CMU skeleton) in which\n"
      "M motifs of 0.5 to 5 s are planted several times each with time warps and noise, and\n"
      "OUT.truth.json listing every planted instance. Streams: any number of frames in bounded\n"
      "memory. With --from, re-sequences real takes instead (realistic neighbour density).";
  SynthOptions defaults;
  spec.options.add_options()("frames", po::value<uint64_t>()->required(), "total frames")(
      "motifs", po::value<uint32_t>()->default_value(defaults.motifs), "planted motifs")(
      "fps", NumberWithDefault(defaults.fps), "frame rate")(
      "from", po::value<std::vector<std::string>>()->multitoken(),
      "re-sequence these real takes (BVH/ASF/AMC files or folders)")(
      "clip-seconds-min", NumberWithDefault(defaults.clip_seconds_min), "")(
      "clip-seconds-max", NumberWithDefault(defaults.clip_seconds_max),
      "clip lengths are drawn from [min, max] seconds")(
      "motif-seconds-min", NumberWithDefault(defaults.motif_seconds_min), "")(
      "motif-seconds-max", NumberWithDefault(defaults.motif_seconds_max),
      "motif lengths are drawn from [min, max] seconds")(
      "instances-min", po::value<uint32_t>()->default_value(defaults.instances_min), "")(
      "instances-max", po::value<uint32_t>()->default_value(defaults.instances_max),
      "planted instances per motif")("noise-degrees",
                                     NumberWithDefault(defaults.noise_degrees),
                                     "noise added to each planted instance (degrees, std dev)")(
      "background-variation", NumberWithDefault(kRecommendedBackgroundVariation),
      "procedural: smooth variation of each background segment (degrees, std dev), so the "
      "background does not repeat")("gap-seconds",
                                    NumberWithDefault(defaults.gap_seconds),
                                    "least untouched background between planted instances")(
      "block-frames", po::value<uint32_t>()->default_value(4096), "frames per column block")(
      "force", "replace OUT.mfs if it exists");
  AddTableFlags(spec, kRunFlags);
  AddProgressOptions(spec);
  spec.positional = {{"out", 1}};
}

// The command line of `synth`, read back (the synthesizer checks the values).
struct SynthCommandOptions {
  SynthOptions synth;
  std::string out;
  bool force = false;
  std::vector<std::string> from;  // real takes to re-sequence; empty: procedural motion
  uint32_t block_frames = 4096;
  ProgressMode progress_mode = ProgressMode::kAuto;
};

SynthCommandOptions ReadSynthOptions(const po::variables_map& vm) {
  SynthCommandOptions command;
  SynthOptions& options = command.synth;
  options.frames = vm["frames"].as<uint64_t>();
  options.motifs = vm["motifs"].as<uint32_t>();
  motifmine::MineOptions table;
  ReadTableFlags(vm, kRunFlags, &table);
  options.seed = table.seed;
  options.fps = vm["fps"].as<double>();
  options.clip_seconds_min = vm["clip-seconds-min"].as<double>();
  options.clip_seconds_max = vm["clip-seconds-max"].as<double>();
  options.motif_seconds_min = vm["motif-seconds-min"].as<double>();
  options.motif_seconds_max = vm["motif-seconds-max"].as<double>();
  options.instances_min = vm["instances-min"].as<uint32_t>();
  options.instances_max = vm["instances-max"].as<uint32_t>();
  options.noise_degrees = vm["noise-degrees"].as<double>();
  options.gap_seconds = vm["gap-seconds"].as<double>();
  options.background_variation_degrees = vm["background-variation"].as<double>();
  options.threads = static_cast<uint32_t>(table.threads);
  command.out = vm["out"].as<std::string>();
  command.force = vm.count("force") > 0;
  if (vm.count("from")) command.from = vm["from"].as<std::vector<std::string>>();
  command.block_frames = vm["block-frames"].as<uint32_t>();
  command.progress_mode = ProgressModeFrom(vm);
  return command;
}

// The procedural synthesizer, or with --from one that re-sequences the real takes.
Result<std::unique_ptr<MotionSynthesizer>> CreateSynthesizer(const SynthCommandOptions& command,
                                                             ProgressReporter* progress) {
  if (command.from.empty()) return MotionSynthesizer::Create(command.synth);
  MOTIF_ASSIGN_OR_RETURN(std::vector<Take> takes,
                         LoadSourceTakes(command.from, command.synth.fps, progress));
  return MotionSynthesizer::CreateFromTakes(command.synth, std::move(takes));
}

}  // namespace

int RunSynth(const std::vector<std::string>& args) {
  CommandSpec spec;
  AddSynthOptions(spec);
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const SynthCommandOptions command = ReadSynthOptions(vm);
  const SynthOptions& options = command.synth;
  std::error_code error;
  if (!command.force && std::filesystem::exists(command.out, error)) {
    return ReportError("synth",
                       Status::InvalidArgument(command.out + ": exists already (use --force to "
                                                             "replace it)"));
  }

  ProgressReporter progress(command.progress_mode);
  Result<std::unique_ptr<MotionSynthesizer>> synthesizer = CreateSynthesizer(command, &progress);
  if (!synthesizer.ok()) return ReportError("synth", synthesizer.status());
  progress.BeginStage("synth", options.frames, "frames");
  Result<uint64_t> frames_done =
      WriteSyntheticArchive(command.out, **synthesizer, options, command.block_frames,
                            [&](uint64_t done, uint64_t) { progress.Update(done); });
  progress.EndStage();
  if (!frames_done.ok()) return ReportError("synth", frames_done.status());
  const std::string truth_path = TruthPathFor(command.out);
  std::printf("wrote %s: %s frames in %s clips at %g fps, %u motifs planted as %zu instances\n",
              command.out.c_str(), WithCommas(*frames_done).c_str(),
              WithCommas((*synthesizer)->clip_count()).c_str(), options.fps, options.motifs,
              (*synthesizer)->truth().size());
  std::printf("wrote %s: the planted instances (ground truth)\n", truth_path.c_str());
  return kExitOk;
}

}  // namespace motif::cli
