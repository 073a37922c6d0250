// The whole job: `motifmine mine ARCHIVE --out DIR --threads 2 -q` (the trellis with
// `--search auto`, the paths, the clustering, the report) run as a child process, against N:
//   MineScale/<data>/frames:N/threads:2   N = 2^14, 2^15, ... up to $MOTIF_BENCH_MAX_FRAMES
//                                          (bench_util.h), one iteration each.
// <data>: "synth" (`motifmine synth ARCHIVE --frames N --motifs M --seed 1`: procedural motion
// with the 12-degree background variation of the synth command, M = clamp(N / 2^14, 1, 20)
// planted motifs) or "resequenced" (the same with `--from ../shared/data/mocap/bvh`: the real
// takes re-sequenced; skipped when they are absent). The archive is written once to
// $MOTIF_BENCH_DIR/mine/ and reused; DIR is removed before and after each run, so every stage
// runs.
// The time is the child's wall time (manual time). Counters: cpu_s (the child's user + system
// CPU seconds, from wait4), peak_rss_bytes (its maximum resident set, ru_maxrss: the whole
// command, nothing of this process), peak_rss_bytes_per_frame, the stages' seconds as the
// command's summary prints them (trellis_s, grow_s, cluster_s, report_s), and on planted
// archives recall, precision and ari (the summary's planted-motif scores).
// The motifmine binary: $MOTIF_MOTIFMINE, else the one built beside this benchmark.
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_util.h"

extern char** environ;

namespace motif {
namespace {

std::string Motifmine() {
  const char* from_env = std::getenv("MOTIF_MOTIFMINE");
  return from_env && *from_env ? from_env : MOTIF_MOTIFMINE_PATH;
}

struct ChildRun {
  int exit_code = -1;
  double wall_seconds = 0;
  double cpu_seconds = 0;
  double peak_rss_bytes = 0;
  std::string output;  // stdout and stderr
};

// Runs `args` (args[0] is the program) with stdout and stderr to `log`, and waits.
ChildRun Run(const std::vector<std::string>& args, const std::string& log) {
  ChildRun run;
  std::vector<char*> argv;
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    run.output = "cannot run " + args[0];
    return run;
  }
  int status = 0;
  struct rusage usage {};
  wait4(pid, &status, 0, &usage);
  run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                    1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  run.peak_rss_bytes = static_cast<double>(usage.ru_maxrss) * 1024.0;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  run.output = text.str();
  return run;
}

// The archive of `data` with `frames` frames (and its truth), written by `motifmine synth` once.
std::string ArchiveOf(const std::string& data, uint64_t frames, std::string* error) {
  const std::string dir = bench::WorkDir() + "/mine";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + data + "-" + std::to_string(frames) + ".mfs";
  const std::string truth = dir + "/" + data + "-" + std::to_string(frames) + ".truth.json";
  if (std::filesystem::exists(path) && std::filesystem::exists(truth)) return path;
  const uint64_t motifs = std::clamp<uint64_t>(frames >> 14, 1, 20);
  std::vector<std::string> args = {Motifmine(),
                                   "synth",
                                   path,
                                   "--frames",
                                   std::to_string(frames),
                                   "--motifs",
                                   std::to_string(motifs),
                                   "--seed",
                                   "1",
                                   "--force",
                                   "-q"};
  if (data == "resequenced") {
    const std::string mocap = bench::MocapDir();
    if (mocap.empty()) {
      *error = "real CMU takes not found: set MOTIF_MOCAP_DIR";
      return "";
    }
    args.insert(args.end(), {"--from", mocap + "/bvh"});
  }
  ChildRun run = Run(args, path + ".log");
  if (run.exit_code != 0) {
    *error = "motifmine synth failed: " + run.output;
    return "";
  }
  return path;
}

// The stages' seconds from the summary line "  time  trellis 12.3s, grow 1.2s, ...; total ...".
std::map<std::string, double> StageSeconds(const std::string& output) {
  std::map<std::string, double> stages;
  std::smatch line;
  if (!std::regex_search(output, line, std::regex(R"(\n\s*time\s+([^\n]*))"))) return stages;
  const std::string text = line[1].str();
  const std::regex part(R"(([a-z]+) ([0-9.]+)s)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), part); it != std::sregex_iterator();
       ++it) {
    stages[(*it)[1].str()] = std::stod((*it)[2].str());
  }
  return stages;
}

// A score from the summary ("  recall       0.950  (...)"); -1 when absent.
double Score(const std::string& output, const std::string& name) {
  std::smatch match;
  const std::regex line("\\n\\s*" + name + R"(\s+(?:ARI\s+)?([0-9.]+))");
  if (std::regex_search(output, match, line)) {
    return std::stod(match[1].str());
  }
  return -1;
}

void BM_MineScale(benchmark::State& state, std::string data) {
  const uint64_t frames = static_cast<uint64_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  std::string error;
  const std::string archive = ArchiveOf(data, frames, &error);
  if (archive.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  const std::string out = archive + ".out";
  ChildRun run;
  for (auto _ : state) {
    std::filesystem::remove_all(out);
    run = Run(
        {Motifmine(), "mine", archive, "--out", out, "--threads", std::to_string(threads), "-q"},
        archive + ".mine.log");
    if (run.exit_code != 0) {
      state.SkipWithError(("motifmine mine failed: " + run.output).c_str());
      break;
    }
    state.SetIterationTime(run.wall_seconds);
  }
  std::filesystem::remove_all(out);
  if (run.exit_code != 0) return;
  bench::SetMemoryCounters(state, run.peak_rss_bytes, 0, frames);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames));
  state.SetComplexityN(static_cast<int64_t>(frames));
  state.counters["cpu_s"] = run.cpu_seconds;
  for (const auto& [stage, seconds] : StageSeconds(run.output)) {
    state.counters[stage + "_s"] = seconds;
  }
  for (const char* score : {"recall", "precision", "grouping"}) {
    const double value = Score(run.output, score);
    if (value >= 0) state.counters[score == std::string("grouping") ? "ari" : score] = value;
  }
  state.SetLabel(run.output.find("lsh search") != std::string::npos ? "lsh search"
                                                                    : "exact search");
}

const bool registered = [] {
  std::vector<std::vector<int64_t>> rows;
  for (int64_t frames : bench::ScalingFrames()) rows.push_back({frames, 2});
  for (const std::string data : {"synth", "resequenced"}) {
    if (auto* family = bench::RegisterRows("MineScale/" + data, rows, BM_MineScale, data)) {
      family->ArgNames({"frames", "threads"})
          ->Unit(benchmark::kSecond)
          ->Iterations(1)
          ->UseManualTime()
          ->Complexity(benchmark::oAuto);
    }
  }
  return true;
}();

}  // namespace
}  // namespace motif

BENCHMARK_MAIN();
