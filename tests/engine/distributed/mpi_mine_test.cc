// motifmine-mpi run by mpirun on this machine, as a user on a cluster would: the same trellis and
// motifs as one process for 1 to 4 ranks, whichever way the archive comes (given, imported,
// synthetic), a usage error printed once, and a rank killed mid-build (docs/design/distributed.md).
// Skipped with a message where mpirun is absent.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "tests/testing/mocap_data.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/shared_inputs.h"
#include "tests/testing/temp_dir.h"

extern char** environ;

namespace motif {
namespace {

namespace fs = std::filesystem;
using testing::RunResult;
using testing::RunShell;
using testing::RunTool;

#define MOTIF_REQUIRE_MPIRUN()                                                           \
  do {                                                                                   \
    if (RunShell("command -v mpirun >/dev/null 2>&1").exit_code != 0) {                  \
      GTEST_SKIP() << "mpirun not found (Debian's openmpi-bin, scripts/install_deps.sh)" \
                      ": skipping this test";                                            \
    }                                                                                    \
  } while (0)

// mpirun as CI runs it: as root, and with more ranks than cores. In the AddressSanitizer build
// the ranks are checked for memory errors but not for leaks: Open MPI's own allocations, held
// until exit in its libraries and plug-ins, are reported as leaks otherwise.
const char kMpirun[] =
    "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
    "ASAN_OPTIONS=\"${ASAN_OPTIONS:-}:detect_leaks=0\" mpirun --oversubscribe ";

std::string Mpirun(int ranks) {
  return kMpirun + std::string("-np ") + std::to_string(ranks) + " " + MOTIF_MPI_TOOL + " ";
}

RunResult RunMpi(int ranks, const std::string& arguments) {
  return RunShell(Mpirun(ranks) + arguments + " 2>&1");
}

std::string Read(const std::string& path) {
  Result<std::string> text = ReadFileToString(path);
  return text.ok() ? *text : "<" + path + ": " + text.status().message() + ">";
}

// A file of /proc, whose size says 0: read to its end.
std::string ReadProc(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A synthetic archive of `frames` frames, made once per build.
std::string SyntheticArchive(uint64_t frames) {
  const std::string folder = testing::SharedInputs(
      "mpi-synth-" + std::to_string(frames) + "-" + testing::ExecutableStamp(MOTIF_TOOL),
      [&](const std::string& dir) {
        RunResult made = RunTool("synth " + dir + "/archive.mfs --frames " +
                                 std::to_string(frames) + " --motifs 6 --seed 3");
        EXPECT_EQ(made.exit_code, 0) << made.output;
        return made.exit_code == 0;
      });
  return folder + "/archive.mfs";
}

// The files of a finished mine that must not depend on how many ranks made them.
void ExpectSameResults(const std::string& expected_dir, const std::string& dir) {
  for (const char* name : {"trellis.mtr", "paths.mpa", "motifs.json"}) {
    EXPECT_TRUE(Read(expected_dir + "/" + name) == Read(dir + "/" + name))
        << name << " of " << dir << " differs from " << expected_dir;
  }
}

TEST(MpiMine, OneToFourRanksGiveOneProcesssTrellisPathsAndMotifsByteForByte) {
  MOTIF_REQUIRE_MPIRUN();
  const std::string archive = SyntheticArchive(30000);
  testing::TempDir dir;
  const std::string options = " --search lsh --threads 1 --no-report --quiet";
  RunResult one = RunTool("mine " + archive + " --out " + dir.File("one") + options);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  ASSERT_NE(Read(dir.File("one/motifs.json")).find("\"instances\""), std::string::npos);
  for (int ranks = 1; ranks <= 4; ++ranks) {
    const std::string out = dir.File("ranks" + std::to_string(ranks));
    RunResult run = RunMpi(ranks, "mine " + archive + " --out " + out + options);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    ExpectSameResults(dir.File("one"), out);
    // Its summary names every rank and what it sent.
    EXPECT_NE(run.output.find("ranks        " + std::to_string(ranks) + ";"), std::string::npos)
        << run.output;
  }
}

TEST(MpiMine, RankZeroMakesTheSyntheticArchiveAndTheExactSearchIsShared) {
  MOTIF_REQUIRE_MPIRUN();
  testing::TempDir dir;
  const std::string options = " --synth-frames 30000 --synth-motifs 3 --threads 1 --quiet";
  RunResult one = RunTool("mine --out " + dir.File("one") + options);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  RunResult three = RunMpi(3, "mine --out " + dir.File("three") + options);
  ASSERT_EQ(three.exit_code, 0) << three.output;
  EXPECT_NE(three.output.find("exact search"), std::string::npos) << three.output;
  EXPECT_TRUE(Read(dir.File("one/archive.mfs")) == Read(dir.File("three/archive.mfs")));
  EXPECT_TRUE(Read(dir.File("one/trellis.mtr")) == Read(dir.File("three/trellis.mtr")));
  // motifs.json names the archive by its path: the folder's name aside, the same bytes.
  std::string motifs = Read(dir.File("three/motifs.json"));
  const std::string three_dir = dir.File("three/");
  for (size_t at = motifs.find(three_dir); at != std::string::npos; at = motifs.find(three_dir)) {
    motifs.replace(at, three_dir.size(), dir.File("one/"));
  }
  EXPECT_EQ(motifs, Read(dir.File("one/motifs.json")));
  EXPECT_TRUE(fs::exists(dir.File("three/report.html")));
}

TEST(MpiMine, ImportedTakesAreMinedAsOneProcessMinesThem) {
  MOTIF_REQUIRE_MPIRUN();
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string takes =
      testing::MocapDir() + "/bvh/01_01.bvh " + testing::MocapDir() + "/bvh/02_05.bvh";
  testing::TempDir dir;
  const std::string options = " --threads 1 --no-report --quiet";
  RunResult one = RunTool("mine " + takes + " --out " + dir.File("one") + options);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  RunResult two = RunMpi(2, "mine " + takes + " --out " + dir.File("two") + options);
  ASSERT_EQ(two.exit_code, 0) << two.output;
  EXPECT_TRUE(Read(dir.File("one/trellis.mtr")) == Read(dir.File("two/trellis.mtr")));
  EXPECT_TRUE(Read(dir.File("one/paths.mpa")) == Read(dir.File("two/paths.mpa")));
}

TEST(MpiMine, AUsageErrorIsPrintedOnceWithItsExitCodeAndMakesNoFolder) {
  MOTIF_REQUIRE_MPIRUN();
  testing::TempDir dir;
  RunResult run = RunMpi(3, "mine --out " + dir.File("out") + " --kmax 0");
  EXPECT_EQ(run.exit_code, 2) << run.output;  // a usage error (docs/guide.md)
  const std::string error = "motifmine mine: --kmax must be a whole number in [1, 65535], not '0'";
  const size_t first = run.output.find(error);
  ASSERT_NE(first, std::string::npos) << run.output;
  EXPECT_EQ(run.output.find(error, first + 1), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir.File("out")));
  RunResult unknown = RunMpi(2, "grow");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("unknown command 'grow'"), std::string::npos) << unknown.output;
}

// Rank 0 in folder A, rank 1 in folder B (mpirun's MPMD form), both reading ARCHIVE by the
// relative path `archive.mfs`: as two nodes without a shared file system.
RunResult RunInTwoFolders(const std::string& a, const std::string& b) {
  const std::string command =
      std::string(" ") + MOTIF_MPI_TOOL + " mine archive.mfs --out out --threads 1 --quiet";
  return RunShell(kMpirun + std::string("-np 1 -wdir ") + a + command + " : -np 1 -wdir " + b +
                  command + " 2>&1");
}

TEST(MpiMine, ARankWithoutTheArchiveOrWithAnotherNamesItselfAndEndsTheJob) {
  MOTIF_REQUIRE_MPIRUN();
  testing::TempDir dir;
  fs::create_directories(dir.File("a"));
  fs::create_directories(dir.File("b"));
  fs::copy_file(SyntheticArchive(30000), dir.File("a/archive.mfs"));
  RunResult missing = RunInTwoFolders(dir.File("a"), dir.File("b"));
  EXPECT_EQ(missing.exit_code, 11) << missing.output;  // not found
  EXPECT_NE(missing.output.find("error: rank 1: the archive rank 0 opened"), std::string::npos)
      << missing.output;
  EXPECT_NE(missing.output.find("archive.mfs: no such file"), std::string::npos) << missing.output;
  EXPECT_FALSE(fs::exists(dir.File("a/out/motifs.json")));
  // Another archive at the same path on rank 1's "node".
  fs::copy_file(SyntheticArchive(240000), dir.File("b/archive.mfs"));
  RunResult other = RunInTwoFolders(dir.File("a"), dir.File("b"));
  EXPECT_NE(other.exit_code, 0) << other.output;
  EXPECT_NE(other.output.find("error: rank 1: the archive rank 0 opened"), std::string::npos)
      << other.output;
  EXPECT_FALSE(fs::exists(dir.File("a/out/motifs.json")));
  EXPECT_FALSE(fs::exists(dir.File("b/out")));  // only rank 0 writes
}

// The process of `rank` of the mpirun job writing into `out_dir`; 0 if none.
pid_t RankProcess(int rank, const std::string& out_dir) {
  for (const fs::directory_entry& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string environment = ReadProc(entry.path().string() + "/environ");
    const std::string command = ReadProc(entry.path().string() + "/cmdline");
    std::replace(environment.begin(), environment.end(), '\0', '\n');
    if (command.find("motifmine-mpi") != std::string::npos &&
        command.find(out_dir) != std::string::npos &&
        ("\n" + environment).find("\nOMPI_COMM_WORLD_RANK=" + std::to_string(rank) + "\n") !=
            std::string::npos) {
      return static_cast<pid_t>(std::stol(name));
    }
  }
  return 0;
}

// `command` started with /bin/sh, its output to `log`.
pid_t Start(const std::string& command, const std::string& log) {
  const std::string line = command + " > " + log + " 2>&1";
  const char* argv[] = {"/bin/sh", "-c", line.c_str(), nullptr};
  pid_t pid = 0;
  if (posix_spawn(&pid, "/bin/sh", nullptr, nullptr, const_cast<char**>(argv), environ) != 0) {
    return 0;
  }
  return pid;
}

TEST(MpiMine, AKilledRankEndsTheJobNamingItAndARerunResumesToTheSameMotifs) {
  MOTIF_REQUIRE_MPIRUN();
  const std::string archive = SyntheticArchive(240000);
  testing::TempDir dir;
  const std::string out = dir.File("killed");
  const std::string options = " --threads 1 --no-report";
  // The reference on two threads: the same files as on one
  // (BuildTrellis.SameBytesForAnyThreadCount).
  RunResult one =
      RunTool("mine " + archive + " --out " + dir.File("one") + " --threads 2 --no-report --quiet");
  ASSERT_EQ(one.exit_code, 0) << one.output;

  const pid_t job =
      Start(Mpirun(2) + "mine " + archive + " --out " + out + options, dir.File("killed.log"));
  ASSERT_GT(job, 0);
  // Once a few blocks are in the partial trellis, rank 1 dies.
  const std::string partial = out + "/trellis.mtr.partial";
  pid_t victim = 0;
  int status = 0;
  for (int wait = 0; wait < 6000 && victim == 0; ++wait) {
    ASSERT_EQ(waitpid(job, &status, WNOHANG), 0) << "the job ended before rank 1 was killed:\n"
                                                 << Read(dir.File("killed.log"));
    std::error_code error;
    if (fs::exists(partial, error) && fs::file_size(partial, error) > 400000) {
      victim = RankProcess(1, out);
    }
    if (victim == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_GT(victim, 0) << "rank 1 not found while the trellis was being built";
  ASSERT_EQ(kill(victim, SIGKILL), 0);
  ASSERT_EQ(waitpid(job, &status, 0), job);
  const std::string log = Read(dir.File("killed.log"));
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) != 0) << log;
  EXPECT_NE(log.find("rank 1"), std::string::npos) << log;
  EXPECT_NE(log.find("signal 9"), std::string::npos) << log;
  // Nothing half-written: the finished blocks, which a rerun resumes from, and the lock.
  std::set<std::string> left;
  for (const fs::directory_entry& entry : fs::directory_iterator(out)) {
    left.insert(entry.path().filename().string());
  }
  EXPECT_EQ(left, (std::set<std::string>{".motifmine.lock", "trellis.mtr.partial"}));

  RunResult again = RunMpi(2, "mine " + archive + " --out " + out + options);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("resuming the interrupted build at column"), std::string::npos)
      << again.output;
  ExpectSameResults(dir.File("one"), out);
}

}  // namespace
}  // namespace motif
