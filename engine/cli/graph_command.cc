// motifmine graph ARCHIVE --start CLIP --seconds S --out DIR [--unconstrained] [--seed N]: a
// motion graph of the archive (engine/graph/), its transitions found in the matching trellis and,
// by default, kept only where the signatures of the motion left and entered agree; then a random
// walk of S seconds from CLIP: DIR/walk.bvh, DIR/walk.json and DIR/graph.json.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "common/file_util.h"
#include "engine/cli/cli_common.h"
#include "engine/cli/words_on_demand.h"
#include "engine/graph/motion_graph.h"
#include "engine/graph/transition_search.h"
#include "engine/graph/transition_signatures.h"
#include "engine/graph/walk_take.h"
#include "engine/pipeline/mine_pipeline.h"
#include "engine/trellis/trellis_builder.h"
#include "formats/export/bvh_writer.h"

namespace motif::cli {
namespace {

namespace po = boost::program_options;

struct GraphRun {
  std::string archive;
  std::string trellis;
  bool constrained = true;
  SignatureConstraint constraint;
  uint64_t candidates = 0;
  double seconds_trellis = 0, seconds_transitions = 0, seconds_signatures = 0, seconds_graph = 0;
};

std::string GraphJson(const MotionGraph& graph, const FrameFileReader& reader,
                      const ClipBounds& clips, const GraphRun& run) {
  const FateCounts fates = CountFates(graph.transitions);
  nlohmann::json json;
  json["version"] = 1;
  json["archive"] = run.archive;
  json["trellis"] = run.trellis;
  json["window_frames"] = graph.window_frames;
  json["constrained"] = run.constrained;
  if (run.constrained) {
    json["signature_window_words"] = kConstraintWindowWords;
    json["signature_threshold"] = run.constraint.threshold;
  }
  json["counts"] = {
      {"candidates", run.candidates},
      {"transitions", graph.transitions.size()},
      {"pruned_signature", fates.signature},
      {"pruned_component", fates.component},
      {"kept", fates.kept},
      {"nodes", graph.nodes.size()},
      {"components", graph.component_sizes.size()},
      {"largest_component_nodes", graph.component_sizes.empty() ? 0 : graph.component_sizes[0]}};
  json["component_sizes"] = graph.component_sizes;
  json["seconds"] = {{"trellis", run.seconds_trellis},
                     {"transitions", run.seconds_transitions},
                     {"signatures", run.seconds_signatures},
                     {"graph", run.seconds_graph}};
  // The node and transition lists are written as text: at 10^6 frames they hold about 10^6
  // objects, which as a JSON document in memory would take gigabytes.
  std::string text = json.dump(1);
  text.pop_back();  // the closing brace, to append the lists
  std::vector<std::string> names;
  for (const ClipInfo& clip : reader.clips()) names.push_back(nlohmann::json(clip.name).dump());
  const auto at = [&](const char* clip_key, const char* frame_key, uint64_t frame) {
    const uint32_t clip = clips.ClipOf(frame);
    return std::string("\"") + clip_key + "\": " + names[clip] + ", \"" + frame_key +
           "\": " + std::to_string(frame - clips.starts[clip]);
  };
  text += ",\n \"nodes\": [";
  for (size_t node = 0; node < graph.nodes.size(); ++node) {
    const int32_t component = graph.component[node];
    text += node ? ",\n  {" : "\n  {";
    text += at("clip", "frame", graph.nodes[node]) +
            ", \"component\": " + (component >= 0 ? std::to_string(component) : "null") + "}";
  }
  text += "\n ],\n \"transitions\": [";
  for (size_t idx = 0; idx < graph.transitions.size(); ++idx) {
    const GraphTransition& edge = graph.transitions[idx];
    text += idx ? ",\n  {" : "\n  {";
    text += at("from_clip", "from_frame", edge.transition.source) + ", " +
            at("to_clip", "to_frame", edge.transition.target) +
            ", \"cost\": " + nlohmann::json(edge.transition.cost).dump() +
            ", \"signature_distance\": " +
            (std::isfinite(edge.signature_distance) ? nlohmann::json(edge.signature_distance).dump()
                                                    : std::string("null")) +
            ", \"fate\": \"" + TransitionFateName(edge.fate) + "\"}";
  }
  text += "\n ]\n}\n";
  return text;
}

nlohmann::json WalkJson(const std::vector<WalkPiece>& pieces, const FrameFileReader& reader,
                        const std::string& start, double seconds, uint64_t seed,
                        uint32_t window_frames, bool constrained) {
  nlohmann::json json;
  json["version"] = 1;
  json["start"] = start;
  json["seconds"] = seconds;
  json["fps"] = reader.fps();
  json["frames"] = WalkFrames(pieces, window_frames);
  json["blend_frames"] = window_frames;
  json["seed"] = seed;
  json["constrained"] = constrained;
  nlohmann::json list = nlohmann::json::array();
  for (const WalkPiece& piece : pieces) {
    list.push_back(
        {{"clip", reader.clips()[piece.clip].name}, {"start", piece.start}, {"end", piece.end}});
  }
  json["pieces"] = list;
  return json;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A finished trellis of this archive is used as it is, whatever options built it (its eps is
// the user's choice); one of another archive version, or none, is built with the defaults: the
// pipeline's trellis stage alone.
Status EnsureGraphTrellis(const FrameFileReader& archive, const std::string& archive_path,
                          const std::string& trellis_path, int threads,
                          ProgressReporter* progress) {
  motifmine::MineOptions options;
  options.threads = threads;
  RunFiles files;
  files.dir = std::filesystem::path(trellis_path).parent_path().string();
  if (files.dir.empty()) files.dir = ".";
  files.archive = archive_path;
  files.trellis = trellis_path;
  RunHooks hooks;
  hooks.progress = [progress](const std::string& stage, uint64_t done, uint64_t total,
                              const std::string& unit) {
    progress->StageUpdate(stage, done, total, unit);
  };
  hooks.note = [progress](const std::string& message) { progress->Note(message); };
  RunSession session(options, {}, files, hooks);
  session.UseArchive(&archive);
  StagePlan plan;
  plan.archive = ArchiveStep::kGiven;
  plan.trellis = TrellisStep::kAnyOfArchive;
  plan.grow = plan.cluster = plan.score = plan.report = plan.run_record = false;
  plan.lock_folder = false;
  const Status status = MinePipeline(&session, plan).Run().status();
  progress->EndStages();
  return status;
}

}  // namespace

int RunGraph(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "graph";
  spec.usage =
      "motifmine graph ARCHIVE --start CLIP --seconds S --out DIR [--unconstrained] [--seed N]";
  spec.summary =
      "Builds a motion graph of ARCHIVE: transitions between frames whose short windows of\n"
      "poses match (found in the matching trellis, ARCHIVE.mtr, built first when missing),\n"
      "local minima of the window's distance, blended over the window; by default a transition\n"
      "is kept only when the signatures of the 12 motion words before it and the 12 after it\n"
      "are close (--unconstrained keeps them all); the largest strongly connected component is\n"
      "kept so a walk never dead-ends. Then walks it at random for S seconds from CLIP.\n"
      "Writes DIR/walk.bvh, DIR/walk.json and DIR/graph.json.";
  spec.options.add_options()("start", po::value<std::string>()->required(),
                             "the clip the walk starts in")(
      "seconds", po::value<double>()->required(), "length of the walk")(
      "out", po::value<std::string>()->required(), "output folder")(
      "unconstrained", po::bool_switch(), "keep transitions whatever their signatures")(
      "seed", po::value<uint64_t>()->default_value(1), "seed of the walk (and of a words build)")(
      "min-piece", po::value<double>()->default_value(1.0),
      "seconds the walk plays after arriving by a transition before it may take another")(
      "window", po::value<double>()->default_value(0.25),
      "seconds of the window matched and blended at a transition")(
      "trellis", po::value<std::string>()->default_value(""), "default: ARCHIVE.mtr")(
      "prefix", po::value<std::string>()->default_value(""),
      "read PREFIX.mwm and PREFIX.mws (default: ARCHIVE without .mfs)")(
      "threads", po::value<int>()->default_value(0), "threads (0: all cores)");
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const auto fail = [](const Status& status) { return ReportError("graph", status); };
  GraphRun run;
  run.archive = vm["archive"].as<std::string>();
  run.constrained = !vm["unconstrained"].as<bool>();
  const double seconds = vm["seconds"].as<double>();
  const double window_seconds = vm["window"].as<double>();
  const uint64_t seed = vm["seed"].as<uint64_t>();
  const int threads = vm["threads"].as<int>();
  if (!(seconds > 0 && seconds <= 86400)) {
    return fail(Status::InvalidArgument("--seconds must be in (0, 86400]"));
  }
  if (!(vm["min-piece"].as<double>() >= 0 && vm["min-piece"].as<double>() <= 3600)) {
    return fail(Status::InvalidArgument("--min-piece must be in [0, 3600] seconds"));
  }
  if (!(window_seconds > 0 && window_seconds <= 5)) {
    return fail(Status::InvalidArgument("--window must be in (0, 5] seconds"));
  }
  Result<std::unique_ptr<FrameFileReader>> opened = FrameFileReader::Open(run.archive);
  if (!opened.ok()) return fail(opened.status());
  const FrameFileReader& reader = **opened;
  const std::string start = vm["start"].as<std::string>();
  uint32_t start_clip = UINT32_MAX;
  for (uint32_t clip = 0; clip < reader.clips().size(); ++clip) {
    if (reader.clips()[clip].name == start) start_clip = clip;
  }
  if (start_clip == UINT32_MAX) {
    return fail(
        Status::NotFound("--start: no clip named '" + start + "' (motifmine info lists them)"));
  }
  const auto window = static_cast<uint32_t>(std::lround(window_seconds * reader.fps()));
  if (window < 2) return fail(Status::InvalidArgument("--window is less than 2 frames"));
  const std::string out = vm["out"].as<std::string>();
  std::error_code error;
  std::filesystem::create_directories(out, error);
  if (error) return fail(Status::IOError("cannot create " + out + ": " + error.message()));
  ProgressReporter progress(ProgressModeFrom(vm));
  const auto stage = [&](const std::string& name, const std::string& unit) {
    return [&, name, unit](uint64_t done, uint64_t total) {
      progress.StageUpdate(name, done, total, unit);
    };
  };

  // The trellis, reused when it is up to date.
  auto clock = std::chrono::steady_clock::now();
  run.trellis = vm["trellis"].as<std::string>();
  if (run.trellis.empty()) run.trellis = DefaultTrellisPath(run.archive);
  if (Status status = EnsureGraphTrellis(reader, run.archive, run.trellis, threads, &progress);
      !status.ok()) {
    return fail(status);
  }
  Result<std::unique_ptr<TrellisFileReader>> trellis = TrellisFileReader::Open(run.trellis);
  if (!trellis.ok()) return fail(trellis.status());
  run.seconds_trellis = SecondsSince(clock);

  clock = std::chrono::steady_clock::now();
  const ClipBounds clips = ClipBoundsOf(reader);
  TransitionOptions transition_options;
  transition_options.window_frames = window;
  transition_options.threads = threads;
  transition_options.progress = stage("transitions", "frames");
  Result<TransitionSearch> found = FindTransitions(**trellis, clips, transition_options);
  progress.EndStages();
  if (!found.ok()) return fail(found.status());
  run.candidates = found->candidates;
  std::vector<GraphTransition> transitions;
  for (const Transition& t : found->transitions) transitions.push_back({t});
  run.seconds_transitions = SecondsSince(clock);

  if (run.constrained) {
    clock = std::chrono::steady_clock::now();
    const std::string prefix = vm["prefix"].as<std::string>();
    const WordsPaths paths = DefaultWordsPaths(prefix.empty() ? run.archive : prefix + ".mfs");
    Result<LoadedWords> words =
        LoadOrBuildWords(run.archive, reader, paths, seed, threads, progress);
    if (!words.ok()) return fail(words.status());
    Result<SignatureConstraint> constraint =
        MeasureTransitionSignatures(reader, *words, clips, &transitions, threads);
    if (!constraint.ok()) return fail(constraint.status());
    run.constraint = *constraint;
    PruneBySignature(constraint->threshold, &transitions);
    run.seconds_signatures = SecondsSince(clock);
  }
  clock = std::chrono::steady_clock::now();
  const MotionGraph graph = BuildMotionGraph(clips, std::move(transitions), window);
  run.seconds_graph = SecondsSince(clock);

  // graph.json first: it explains a walk that cannot start.
  const std::filesystem::path dir(out);
  if (Status status =
          AtomicWriteFile((dir / "graph.json").string(), GraphJson(graph, reader, clips, run));
      !status.ok()) {
    return fail(status);
  }
  const auto frames = static_cast<uint64_t>(std::llround(seconds * reader.fps()));
  WalkOptions walk_options;
  walk_options.frames = frames;
  walk_options.seed = seed;
  walk_options.min_piece_frames =
      static_cast<uint64_t>(std::llround(vm["min-piece"].as<double>() * reader.fps()));
  Result<std::vector<WalkPiece>> pieces = RandomWalk(graph, clips, start_clip, walk_options);
  if (!pieces.ok()) return fail(pieces.status());
  Result<Take> walk = WalkTake(reader, *pieces, window);
  if (!walk.ok()) return fail(walk.status());
  if (Status status = WriteBvh(*walk, (dir / "walk.bvh").string()); !status.ok()) {
    return fail(status);
  }
  if (Status status = AtomicWriteFile(
          (dir / "walk.json").string(),
          WalkJson(*pieces, reader, start, seconds, seed, window, run.constrained).dump(2) + "\n");
      !status.ok()) {
    return fail(status);
  }

  const FateCounts fates = CountFates(graph.transitions);
  std::printf("motifmine graph: %s (%s frames in %zu clips)\n", run.archive.c_str(),
              WithCommas(reader.frame_count()).c_str(), reader.clips().size());
  std::printf("  transitions  %s window pairs within eps, %s local minima (window %u frames)\n",
              WithCommas(run.candidates).c_str(), WithCommas(graph.transitions.size()).c_str(),
              window);
  if (run.constrained) {
    std::printf(
        "  constraint   %s pruned: signature distance of %u words above %.4f (the median "
        "change within a take)\n",
        WithCommas(fates.signature).c_str(), kConstraintWindowWords, run.constraint.threshold);
  } else {
    std::printf("  constraint   none (--unconstrained)\n");
  }
  std::printf(
      "  components   %zu (largest %s of %s nodes); %s transitions pruned between "
      "them; %s kept\n",
      graph.component_sizes.size(),
      WithCommas(graph.component_sizes.empty() ? 0 : graph.component_sizes[0]).c_str(),
      WithCommas(graph.nodes.size()).c_str(), WithCommas(fates.component).c_str(),
      WithCommas(fates.kept).c_str());
  std::printf("  walk         %.1f s from %s in %zu pieces (seed %llu)\n", seconds, start.c_str(),
              pieces->size(), static_cast<unsigned long long>(seed));
  std::printf("  time         trellis %.1fs, transitions %.1fs, signatures %.1fs, graph %.1fs\n",
              run.seconds_trellis, run.seconds_transitions, run.seconds_signatures,
              run.seconds_graph);
  std::printf("  wrote        %s, %s, %s\n", (dir / "walk.bvh").c_str(),
              (dir / "walk.json").c_str(), (dir / "graph.json").c_str());
  return kExitOk;
}

}  // namespace motif::cli
