// `motifmine mine` killed (SIGKILL) at each stage and run again finishes with the same
// motifs.json, byte for byte, as an uninterrupted run; a further identical run reuses every
// stage, and no temporary file of the killed run is left in DIR. The tool runs as a child
// process with --progress json; its progress lines on stderr say which stage it is in, and it is
// killed when a given stage has begun (synth, trellis features, trellis, grow, cluster), or, in
// the middle of the trellis, once the partial trellis file holds a whole column block (the rerun
// must then say it resumes there). Once with the exact search (what `auto` picks for this small
// archive), once mid-trellis with LSH.
//
// Every run uses the same relative --out ("out") from its own working directory, so the archive
// path that motifs.json records is the same for all of them.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

// Small enough for the whole test to take well under a minute, big enough that the exact
// trellis has several column blocks (4096 columns each) to interrupt between.
const std::vector<std::string> kMineArgs = {"mine",  "--out",          "out", "--synth-frames",
                                            "10000", "--synth-motifs", "2",   "--seed",
                                            "4",     "--kmax",         "64"};

struct ChildRun {
  bool killed = false;  // ended by our SIGKILL
  int exit_code = -1;   // when it exited by itself
  std::string trigger;  // what it was killed at
  std::string log;      // stderr
};

// Decides when to kill: called with each progress line (JSON on stderr) as it arrives, and with
// nullptr every few milliseconds in between, to look at the files in `cwd`.
using Trigger = std::function<bool(const nlohmann::json* line, const std::string& cwd)>;

// Runs the tool in `cwd` with `args`; kills it with SIGKILL as soon as `when` says so.
ChildRun RunUntil(const std::string& cwd, std::vector<std::string> args, const Trigger& when) {
  ChildRun run;
  int fds[2];
  if (::pipe(fds) != 0) return run;
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(cwd.c_str()) != 0) ::_exit(127);
    ::dup2(fds[1], 2);
    const int null_fd = ::open("/dev/null", O_WRONLY);
    ::dup2(null_fd, 1);
    ::close(fds[0]);
    ::close(fds[1]);
    std::vector<char*> argv;
    std::string tool = MOTIF_TOOL;
    argv.push_back(tool.data());
    for (std::string& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    ::execv(tool.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  bool sent = false;
  const auto kill_at = [&](const std::string& what) {
    ::kill(pid, SIGKILL);
    sent = true;
    run.trigger = what;
  };
  std::string pending;  // an incomplete last line
  char buffer[4096];
  for (;;) {
    pollfd poll_fd{fds[0], POLLIN, 0};
    const int ready = ::poll(&poll_fd, 1, /*timeout_ms=*/2);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) {
      if (!sent && when(nullptr, cwd)) kill_at("a check of the output files\n");
      continue;
    }
    const ssize_t got = ::read(fds[0], buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    run.log.append(buffer, static_cast<size_t>(got));
    pending.append(buffer, static_cast<size_t>(got));
    for (size_t end = pending.find('\n'); end != std::string::npos; end = pending.find('\n')) {
      const std::string line = pending.substr(0, end + 1);
      pending.erase(0, end + 1);
      if (sent) continue;
      const nlohmann::json progress = nlohmann::json::parse(line, nullptr, false);
      if (progress.is_object() && when(&progress, cwd)) kill_at(line);
    }
  }
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  run.killed = WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
  if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  return run;
}

ChildRun RunToEnd(const std::string& cwd, std::vector<std::string> args) {
  return RunUntil(cwd, std::move(args),
                  [](const nlohmann::json*, const std::string&) { return false; });
}

std::vector<std::string> With(std::vector<std::string> args, const std::string& extra) {
  args.push_back(extra);
  return args;
}

// A stage begins when its first progress line appears.
Trigger StageBegun(const std::string& stage) {
  return [stage](const nlohmann::json* line, const std::string&) {
    return line != nullptr && line->value("stage", "") == stage && line->contains("done");
  };
}

// After the trellis stage has written its first column block whole, and before it ends. Progress
// lines are drawn at most a few times a second, so the block is seen in the file: the partial
// trellis holds just its header when the stage begins, then the blocks follow, each with its size
// in its header (docs/formats/trellis_file.md 4.3: 48 + ids_bytes (u32 at +0x18) +
// distances_bytes (u32 at +0x1c) bytes).
Trigger MidTrellis() {
  auto header_bytes = std::make_shared<int64_t>(-1);
  return [header_bytes](const nlohmann::json* line, const std::string& cwd) {
    const std::string partial = cwd + "/out/trellis.mtr.partial";
    std::error_code error;
    const auto size = static_cast<int64_t>(std::filesystem::file_size(partial, error));
    if (line != nullptr && line->value("stage", "") == "trellis" && *header_bytes < 0) {
      *header_bytes = error ? 0 : size;
      return false;
    }
    if (*header_bytes <= 0 || error || size < *header_bytes + 48) return false;
    std::ifstream file(partial, std::ios::binary);
    file.seekg(*header_bytes + 0x18);
    unsigned char sizes[8] = {};
    if (!file.read(reinterpret_cast<char*>(sizes), sizeof sizes)) return false;
    const auto u32 = [&](int at) {
      return static_cast<int64_t>(sizes[at]) | static_cast<int64_t>(sizes[at + 1]) << 8 |
             static_cast<int64_t>(sizes[at + 2]) << 16 | static_cast<int64_t>(sizes[at + 3]) << 24;
    };
    return size >= *header_bytes + 48 + u32(0) + u32(4);
  };
}

// The tool's stdout and stderr, run in `cwd`.
std::string Stdout(const std::string& cwd, const std::vector<std::string>& args) {
  std::string command = "cd '" + cwd + "' && '" + std::string(MOTIF_TOOL) + "'";
  for (const std::string& arg : args) command += " " + arg;
  command += " 2>&1";
  std::string output;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return output;
  char buffer[4096];
  size_t read = 0;
  while ((read = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, read);
  ::pclose(pipe);
  return output;
}

struct Scenario {
  std::string name;
  Trigger when;
  bool must_be_killed;  // false: the stage is so short that the run may end before the signal
  bool resumes_trellis = false;  // the rerun continues the trellis after its written blocks
};

// The uninterrupted run's motifs.json, made in `cwd`.
std::string ReferenceMotifs(const std::string& cwd, const std::vector<std::string>& args) {
  std::filesystem::create_directories(cwd);
  ChildRun reference = RunToEnd(cwd, With(args, "--progress=json"));
  EXPECT_EQ(reference.exit_code, 0) << reference.log;
  auto motifs = ReadFileToString(cwd + "/out/motifs.json");
  EXPECT_TRUE(motifs.ok()) << reference.log;
  return motifs.ok() ? *motifs : "";
}

// Kills a run in a fresh `cwd` as `scenario` says, runs it again to the end and compares; then
// once more, which must reuse every stage.
void KillRerunAndCompare(const std::string& cwd, const std::vector<std::string>& args,
                         const Scenario& scenario, const std::string& expected) {
  SCOPED_TRACE("killed at " + scenario.name);
  std::filesystem::create_directories(cwd);
  ChildRun killed = RunUntil(cwd, With(args, "--progress=json"), scenario.when);
  ASSERT_FALSE(killed.trigger.empty()) << "the stage never began\n" << killed.log;
  if (scenario.must_be_killed) {
    EXPECT_TRUE(killed.killed) << killed.log;
  }
  std::cout << "[ killed   ] at " << scenario.name << ": "
            << (killed.killed ? "killed by SIGKILL" : "had already finished") << " after "
            << killed.trigger;

  ChildRun rerun = RunToEnd(cwd, With(args, "--progress=json"));
  ASSERT_EQ(rerun.exit_code, 0) << rerun.log;
  if (scenario.resumes_trellis) {
    const size_t note = rerun.log.find("resuming the interrupted build at column");
    ASSERT_NE(note, std::string::npos) << rerun.log;
    std::cout << "[ rerun    ] " << rerun.log.substr(note, rerun.log.find('"', note) - note)
              << "\n";
  }
  auto motifs = ReadFileToString(cwd + "/out/motifs.json");
  ASSERT_TRUE(motifs.ok()) << rerun.log;
  EXPECT_TRUE(*motifs == expected) << "motifs.json differs from the uninterrupted run's";

  // The same again: nothing left to do.
  const std::string again = Stdout(cwd, With(args, "--quiet"));
  for (const char* stage : {"synth", "trellis", "grow", "cluster"}) {
    EXPECT_TRUE(std::regex_search(again, std::regex(std::string(stage) + " [0-9.]+s \\(reused\\)")))
        << stage << " was not reused\n"
        << again;
  }
  auto motifs_again = ReadFileToString(cwd + "/out/motifs.json");
  ASSERT_TRUE(motifs_again.ok());
  EXPECT_TRUE(*motifs_again == expected);
  // Nothing else is left behind: no temporary file of the killed run.
  for (const auto& entry : std::filesystem::directory_iterator(cwd + "/out")) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "archive.mfs" || name == "archive.truth.json" || name == "trellis.mtr" ||
                name == "paths.mpa" || name == "motifs.json" || name == "instances.csv" ||
                name == "mine_state.json" || name == "report.html" || name == "run.json" ||
                name == ".motifmine.lock")
        << "left behind: " << name;
  }
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(MineInterrupt, KilledAtEachStageThenRerunGivesTheSameMotifs) {
  const auto start = std::chrono::steady_clock::now();
  testing::TempDir dir;
  const std::string expected = ReferenceMotifs(dir.File("reference"), kMineArgs);
  ASSERT_FALSE(expected.empty());
  const std::vector<Scenario> scenarios = {
      {"synth", StageBegun("synth"), true},
      {"trellis features", StageBegun("trellis features"), true},
      {"trellis", StageBegun("trellis"), true},
      {"mid-trellis", MidTrellis(), true, true},
      {"grow", StageBegun("grow"), false},
      {"cluster", StageBegun("cluster"), false},
  };
  for (size_t idx = 0; idx < scenarios.size(); ++idx) {
    KillRerunAndCompare(dir.File("killed-" + std::to_string(idx)), kMineArgs, scenarios[idx],
                        expected);
  }
  std::cout << "[ time     ] " << SecondsSince(start) << " s\n";
}

// The LSH search (the one large archives use) resumes an interrupted trellis to the same result.
TEST(MineInterrupt, LshTrellisKilledMidwayResumesToTheSameMotifs) {
  const auto start = std::chrono::steady_clock::now();
  testing::TempDir dir;
  const std::vector<std::string> args = With(With(kMineArgs, "--search"), "lsh");
  const std::string expected = ReferenceMotifs(dir.File("reference"), args);
  ASSERT_FALSE(expected.empty());
  KillRerunAndCompare(dir.File("killed"), args, {"mid-trellis (lsh)", MidTrellis(), true, true},
                      expected);
  std::cout << "[ time     ] " << SecondsSince(start) << " s\n";
}

}  // namespace
}  // namespace motif
