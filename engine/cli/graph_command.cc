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
#include "engine/cli/mined_folder.h"
#include "engine/cli/table_options.h"
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

// The command line of a run, checked.
struct GraphArgs {
  std::string mined_folder;
  std::string start;
  std::string out;
  std::string prefix;
  double seconds = 0;
  double window_seconds = 0;
  double min_piece_seconds = 0;
  uint64_t seed = 1;
  int threads = 0;
};

CommandSpec GraphCommandSpec() {
  CommandSpec spec;
  spec.name = "graph";
  spec.usage =
      "motifmine graph ARCHIVE --start CLIP --seconds S --out DIR [--unconstrained] [--seed N]";
  spec.summary =
      "Builds a motion graph of ARCHIVE: transitions between frames whose short windows of\n"
      "poses match (found in the matching trellis: the one `mine` wrote when ARCHIVE is its\n"
      "output folder, else ARCHIVE.mtr, built first when missing),\n"
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
      "min-piece", NumberWithDefault(1.0),
      "seconds the walk plays after arriving by a transition before it may take another")(
      "window", NumberWithDefault(0.25),
      "seconds of the window matched and blended at a transition")(
      "trellis", po::value<std::string>()->default_value(""),
      "default: the trellis `mine` wrote beside ARCHIVE when it is of this archive version, "
      "else ARCHIVE.mtr")(
      "prefix", po::value<std::string>()->default_value(""),
      "read PREFIX.mwm and PREFIX.mws (default: ARCHIVE without .mfs)");
  AddTableFlags(spec, kRunFlags);
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  return spec;
}

// The numbers are in their ranges already (CheckNumericOptions, numeric_options.h).
void ReadGraphArgs(const po::variables_map& vm, GraphArgs* args, GraphRun* run) {
  run->archive = vm["archive"].as<std::string>();
  run->constrained = !vm["unconstrained"].as<bool>();
  run->trellis = vm["trellis"].as<std::string>();
  // Where `mine` may have left a trellis: the folder given as ARCHIVE, else the archive's.
  args->mined_folder = vm.count(kMinedFolderKey)
                           ? vm[kMinedFolderKey].as<std::string>()
                           : std::filesystem::path(run->archive).parent_path().string();
  args->start = vm["start"].as<std::string>();
  args->out = vm["out"].as<std::string>();
  args->prefix = vm["prefix"].as<std::string>();
  args->seconds = vm["seconds"].as<double>();
  args->window_seconds = vm["window"].as<double>();
  args->min_piece_seconds = vm["min-piece"].as<double>();
  motifmine::MineOptions table;
  ReadTableFlags(vm, kRunFlags, &table);
  args->seed = table.seed;
  args->threads = table.threads;
}

Result<uint32_t> StartClip(const FrameFileReader& reader, const std::string& start) {
  for (uint32_t clip = 0; clip < reader.clips().size(); ++clip) {
    if (reader.clips()[clip].name == start) return clip;
  }
  return Status::NotFound("--start: no clip named '" + start + "' (motifmine info lists them)");
}

// The trellis (reused when it is up to date), its transitions, kept by their signatures when
// constrained, and the graph of them.
Result<MotionGraph> BuildGraph(const FrameFileReader& reader, const GraphArgs& args,
                               uint32_t window, GraphRun* run, ProgressReporter* progress) {
  auto clock = std::chrono::steady_clock::now();
  // Not given: the trellis `mine` left beside the archive when it is of this version, else
  // ARCHIVE.mtr.
  if (run->trellis.empty()) run->trellis = MinedTrellisOf(args.mined_folder, reader);
  if (run->trellis.empty()) run->trellis = DefaultTrellisPath(run->archive);
  MOTIF_RETURN_IF_ERROR(
      EnsureGraphTrellis(reader, run->archive, run->trellis, args.threads, progress));
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<TrellisFileReader> trellis,
                         TrellisFileReader::Open(run->trellis));
  run->seconds_trellis = SecondsSince(clock);
  clock = std::chrono::steady_clock::now();
  const ClipBounds clips = ClipBoundsOf(reader);
  TransitionOptions transition_options;
  transition_options.window_frames = window;
  transition_options.threads = args.threads;
  transition_options.progress = [progress](uint64_t done, uint64_t total) {
    progress->StageUpdate("transitions", done, total, "frames");
  };
  Result<TransitionSearch> found = FindTransitions(*trellis, clips, transition_options);
  progress->EndStages();
  MOTIF_RETURN_IF_ERROR(found.status());
  run->candidates = found->candidates;
  std::vector<GraphTransition> transitions;
  for (const Transition& t : found->transitions) transitions.push_back({t});
  run->seconds_transitions = SecondsSince(clock);
  if (run->constrained) {
    clock = std::chrono::steady_clock::now();
    const WordsPaths paths =
        DefaultWordsPaths(args.prefix.empty() ? run->archive : args.prefix + ".mfs");
    MOTIF_ASSIGN_OR_RETURN(LoadedWords words, LoadOrBuildWords(run->archive, reader, paths,
                                                               args.seed, args.threads, *progress));
    MOTIF_ASSIGN_OR_RETURN(run->constraint, MeasureTransitionSignatures(
                                                reader, words, clips, &transitions, args.threads));
    PruneBySignature(run->constraint.threshold, &transitions);
    run->seconds_signatures = SecondsSince(clock);
  }
  clock = std::chrono::steady_clock::now();
  MotionGraph graph = BuildMotionGraph(clips, std::move(transitions), window);
  run->seconds_graph = SecondsSince(clock);
  return graph;
}

// DIR/graph.json first (it explains a walk that cannot start), then the walk: DIR/walk.bvh and
// DIR/walk.json. The walk's pieces.
Result<std::vector<WalkPiece>> WriteGraphAndWalk(const FrameFileReader& reader,
                                                 const MotionGraph& graph, const GraphArgs& args,
                                                 uint32_t start_clip, uint32_t window,
                                                 const GraphRun& run) {
  const std::filesystem::path dir(args.out);
  const ClipBounds clips = ClipBoundsOf(reader);
  MOTIF_RETURN_IF_ERROR(
      AtomicWriteFile((dir / "graph.json").string(), GraphJson(graph, reader, clips, run)));
  WalkOptions walk_options;
  walk_options.frames = static_cast<uint64_t>(std::llround(args.seconds * reader.fps()));
  walk_options.seed = args.seed;
  walk_options.min_piece_frames =
      static_cast<uint64_t>(std::llround(args.min_piece_seconds * reader.fps()));
  MOTIF_ASSIGN_OR_RETURN(std::vector<WalkPiece> pieces,
                         RandomWalk(graph, clips, start_clip, walk_options));
  MOTIF_ASSIGN_OR_RETURN(Take walk, WalkTake(reader, pieces, window));
  MOTIF_RETURN_IF_ERROR(WriteBvh(walk, (dir / "walk.bvh").string()));
  MOTIF_RETURN_IF_ERROR(AtomicWriteFile(
      (dir / "walk.json").string(),
      WalkJson(pieces, reader, args.start, args.seconds, args.seed, window, run.constrained)
              .dump(2) +
          "\n"));
  return pieces;
}

void PrintGraphSummary(const FrameFileReader& reader, const MotionGraph& graph,
                       const GraphArgs& args, const GraphRun& run, uint32_t window, size_t pieces) {
  const std::filesystem::path dir(args.out);
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
  std::printf("  walk         %.1f s from %s in %zu pieces (seed %llu)\n", args.seconds,
              args.start.c_str(), pieces, static_cast<unsigned long long>(args.seed));
  std::printf("  time         trellis %.1fs, transitions %.1fs, signatures %.1fs, graph %.1fs\n",
              run.seconds_trellis, run.seconds_transitions, run.seconds_signatures,
              run.seconds_graph);
  std::printf("  wrote        %s, %s, %s\n", (dir / "walk.bvh").c_str(),
              (dir / "walk.json").c_str(), (dir / "graph.json").c_str());
}

}  // namespace

int RunGraph(const std::vector<std::string>& args) {
  CommandSpec spec = GraphCommandSpec();
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const auto fail = [](const Status& status) { return ReportError("graph", status); };
  GraphArgs graph_args;
  GraphRun run;
  ReadGraphArgs(vm, &graph_args, &run);
  Result<std::unique_ptr<FrameFileReader>> opened = FrameFileReader::Open(run.archive);
  if (!opened.ok()) return fail(opened.status());
  const FrameFileReader& reader = **opened;
  Result<uint32_t> start_clip = StartClip(reader, graph_args.start);
  if (!start_clip.ok()) return fail(start_clip.status());
  const auto window = static_cast<uint32_t>(std::lround(graph_args.window_seconds * reader.fps()));
  if (window < 2) return fail(Status::InvalidArgument("--window is less than 2 frames"));
  std::error_code error;
  std::filesystem::create_directories(graph_args.out, error);
  if (error) {
    return fail(Status::IOError("cannot create " + graph_args.out + ": " + error.message()));
  }
  ProgressReporter progress(ProgressModeFrom(vm));
  Result<MotionGraph> graph = BuildGraph(reader, graph_args, window, &run, &progress);
  if (!graph.ok()) return fail(graph.status());
  Result<std::vector<WalkPiece>> pieces =
      WriteGraphAndWalk(reader, *graph, graph_args, *start_clip, window, run);
  if (!pieces.ok()) return fail(pieces.status());
  PrintGraphSummary(reader, *graph, graph_args, run, window, pieces->size());
  return kExitOk;
}

}  // namespace motif::cli
