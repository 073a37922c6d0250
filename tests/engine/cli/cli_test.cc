// End-to-end tests of the motifmine tool: runs the built binary as a user would.

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/import/take_importer.h"
#include "formats/motion/quaternion_math.h"
#include "tests/testing/mocap_data.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/tmpfs.h"

namespace motif {
namespace {

using testing::RunResult;
using testing::RunShell;
using testing::RunTool;

TEST(MotifmineTool, HelpForEveryCommand) {
  for (const char* command : {"import", "info", "verify", "export", "synth"}) {
    RunResult result = RunTool(std::string(command) + " --help");
    EXPECT_EQ(result.exit_code, 0) << command << ": " << result.output;
    EXPECT_NE(result.output.find("usage: motifmine " + std::string(command)), std::string::npos);
  }
  // Every command's defaults as a person writes them: "0.2", never "0.20000000000000001".
  for (const char* command :
       {"mine", "reindex", "import", "info", "verify", "export", "synth", "trellis",
        "inspect-trellis", "grow", "cluster", "report", "score", "export-motif", "words", "search",
        "classify", "segment", "graph"}) {
    const std::string help = RunTool(std::string(command) + " --help").output;
    EXPECT_EQ(help.find("0000000"), std::string::npos) << command << ":\n" << help;
    EXPECT_EQ(help.find("9999999"), std::string::npos) << command << ":\n" << help;
  }
  EXPECT_EQ(RunTool("frobnicate").exit_code, 2);
  EXPECT_EQ(RunTool("info").exit_code, 2);  // missing ARCHIVE
  EXPECT_EQ(RunTool("synth x.mfs --frames").exit_code, 2);
}

// A negative count, a negative thread count, a number that is not finite or an impossible
// frame rate is a usage error naming the flag and the value, before anything is read or
// written; boost's parser alone turned --kmax=-1 into 4294967295 and --fps 5e7 into an
// allocation that failed.
TEST(MotifmineTool, NumbersOutOfRangeAreUsageErrorsNamingTheFlag) {
  testing::TempDir dir;
  const std::string archive = dir.File("a.mfs");
  const std::string out = dir.File("out");
  const std::string mine = "mine " + archive + " --out " + out + " --quiet --no-report ";
  const std::pair<std::string, std::string> cases[] = {
      {mine + "--kmax=-1", "--kmax must be a whole number in [1, 65535], not '-1'"},
      {mine + "--kmax -1", "--kmax must be a whole number in [1, 65535], not '-1'"},
      {mine + "--exclusion=-5", "--exclusion must be a whole number in [0, 1000000000], not '-5'"},
      {mine + "--threads -1", "--threads must be a whole number in [0, 4096], not '-1'"},
      {mine + "--eps nan", "--eps must be auto or a number in [0, 1000000] (0: auto), not 'nan'"},
      {mine + "--eps inf", "--eps must be auto or a number in [0, 1000000] (0: auto), not 'inf'"},
      {"export " + archive + " --clip c --start=-1 --out " + dir.File("x.bvh"),
       "--start must be a whole number >= 0, not '-1'"},
      {"import " + archive + " " + dir.path() + " --fps 5e7",
       "--fps must be 0 (not given) or a number in [1, 10000], not '5e7'"},
      {"import " + archive + " " + dir.path() + " --fps nan",
       "--fps must be 0 (not given) or a number in [1, 10000], not 'nan'"},
      {"import " + archive + " " + dir.path() + " --bvh-fps 1e-9",
       "--bvh-fps must be 0 (not given) or a number in [1, 10000], not '1e-9'"},
      {"synth " + archive + " --frames=-3000",
       "--frames must be a whole number in [1, 100000000], not '-3000'"},
      {"mine " + archive + " --out " + dir.File("m") + " --pause-speed=-3",
       "--pause-speed must be a number in [0, 1000000], not '-3'"},
      {"cluster " + archive + " --out " + dir.File("m") + " --pause-seconds 0",
       "--pause-seconds must be a number in (0, 3600], not '0'"},
      {mine + "--playback-mb 5000",
       "--playback-mb must be a whole number in [0, 4096], not '5000'"},
      {"report " + dir.File("m") + " --playback-mb 4097",
       "--playback-mb must be a whole number in [0, 4096], not '4097'"},
      {"export " + archive + " --clip c --names x --out " + dir.File("x.bvh"),
       "--names must be source or canonical, not 'x'"},
      // Bounds that a run would otherwise find out the hard way: TBB fails beyond the threads a
      // process may create, and a synthetic archive writes until the disk is full.
      {mine + "--threads 65537", "--threads must be a whole number in [0, 4096], not '65537'"},
      {"trellis " + archive + " --threads 65537",
       "--threads must be a whole number in [0, 4096], not '65537'"},
      {"reindex " + archive + " --watch " + dir.path() + " --out " + out + " --threads 65537",
       "--threads must be a whole number in [0, 4096], not '65537'"},
      {"synth " + archive + " --frames 99999999999",
       "--frames must be a whole number in [1, 100000000], not '99999999999'"},
      {"mine --out " + out + " --synth-frames 99999999999",
       "--synth-frames must be a whole number in [1, 100000000], not '99999999999'"},
      {"reindex " + archive + " --watch " + dir.path() + " --out " + out + " --min-age -1",
       "--min-age must be a number in [0, 31536000], not '-1'"},
      {"reindex " + archive + " --watch " + dir.path() + " --out " + out + " --min-similarity -5",
       "--min-similarity must be a number in (0, 1], not '-5'"},
  };
  for (const auto& [args, message] : cases) {
    const RunResult result = RunTool(args);
    EXPECT_EQ(result.exit_code, 2) << args << "\n" << result.output;
    EXPECT_NE(result.output.find(message), std::string::npos) << args << "\n" << result.output;
  }
  EXPECT_FALSE(std::filesystem::exists(archive)) << "nothing is written";
  EXPECT_FALSE(std::filesystem::exists(out));
  // 0 still means "not given" for the rates, and in-range values still parse.
  EXPECT_EQ(RunTool("synth " + archive + " --frames 2000 --motifs 0 --fps 60 --quiet").exit_code,
            0);
}

// A FIFO or a device named as a take is refused at once (exit 13, the file named): a plain open
// of a FIFO waits for a writer forever, holding the archive's lock, and /dev/zero never ends.
TEST(MotifmineTool, AFifoOrADeviceNamedAsATakeIsRefusedAtOnce) {
  testing::TempDir dir;
  const std::string fifo = dir.File("fifo.bvh");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string zero = dir.File("zero.bvh");
  std::filesystem::create_symlink("/dev/zero", zero);
  const std::string archive = dir.File("a.mfs");
  for (const std::string& take : {fifo, zero}) {
    for (const std::string& command :
         {"import " + archive + " " + take,
          "mine " + take + " --out " + dir.File("out") + " --quiet --no-report"}) {
      const RunResult result = RunTool(command);
      EXPECT_EQ(result.exit_code, 13) << command << "\n" << result.output;
      EXPECT_NE(result.output.find(take + ": not a regular file"), std::string::npos)
          << command << "\n"
          << result.output;
    }
  }
  EXPECT_FALSE(std::filesystem::exists(archive));
  // A folder named like a take is searched as a folder, and the error says so.
  const std::string folder = dir.File("x.bvh");
  std::filesystem::create_directories(folder);
  const RunResult empty = RunTool("import " + archive + " " + folder);
  EXPECT_EQ(empty.exit_code, 13) << empty.output;
  EXPECT_NE(empty.output.find("no .bvh or .amc takes found in " + folder + " (a folder)"),
            std::string::npos)
      << empty.output;
}

// A take file larger than the limit (1 GiB) is refused on its size before it is read (a sparse
// file here: nothing is written to disk), by itself or passed over with --skip-bad.
TEST(MotifmineTool, ATakeLargerThanTheLimitIsRefusedBeforeItIsRead) {
  testing::TempDir dir;
  const std::string huge = dir.File("huge.bvh");
  ASSERT_EQ(::truncate(huge.c_str(), 0), -1);  // absent
  { std::ofstream create(huge); }
  ASSERT_EQ(::truncate(huge.c_str(), (int64_t{1} << 30) + 1), 0);
  const std::string archive = dir.File("a.mfs");
  const RunResult refused = RunTool("import " + archive + " " + huge);
  EXPECT_EQ(refused.exit_code, 13) << refused.output;
  EXPECT_NE(refused.output.find(huge + ": 1073741825 bytes, more than the 1073741824 allowed"),
            std::string::npos)
      << refused.output;
  EXPECT_FALSE(std::filesystem::exists(archive));

  const std::string synth = dir.File("s.mfs");
  ASSERT_EQ(RunTool("synth " + synth + " --frames 6000 --motifs 1 --seed 2 --quiet").exit_code, 0);
  ASSERT_EQ(
      RunTool("export " + synth + " --clip synth_000000 --out " + dir.File("good.bvh")).exit_code,
      0);
  const RunResult skipped = RunTool("import " + archive + " " + dir.File("good.bvh") + " " + huge +
                                    " --skip-bad --quiet");
  EXPECT_EQ(skipped.exit_code, 3) << skipped.output;
  EXPECT_NE(skipped.output.find(huge), std::string::npos) << skipped.output;
  EXPECT_EQ(nlohmann::json::parse(RunTool("info " + archive + " --json").output)["clips"].size(),
            1u);
}

// motifs.json names its archive relative to its own folder: a run made with relative paths in
// one directory is reported and exported from any other.
TEST(MotifmineTool, ReportAndExportMotifWorkFromAnyDirectory) {
  testing::TempDir dir;
  const std::string in_dir = "cd " + dir.path() + " && " + MOTIF_TOOL + " ";
  ASSERT_EQ(RunShell(in_dir + "synth s.mfs --frames 6000 --motifs 1 --seed 2 --quiet").exit_code,
            0);
  ASSERT_EQ(RunShell(in_dir + "mine s.mfs --out out --quiet --no-report").exit_code, 0);
  const nlohmann::json motifs =
      nlohmann::json::parse(ReadFileToString(dir.File("out/motifs.json")).value());
  EXPECT_EQ(motifs["archive"], "../s.mfs");
  const RunResult report =
      RunTool("report " + dir.File("out") + " --out " + dir.File("report.html"));
  EXPECT_EQ(report.exit_code, 0) << report.output;
  const RunResult exported =
      RunTool("export-motif " + dir.File("out") + " --motif 0 --out " + dir.File("m0"));
  EXPECT_EQ(exported.exit_code, 0) << exported.output;
  EXPECT_FALSE(std::filesystem::is_empty(dir.File("m0")));

  // verify on the mine output folder checks its files (it said "out/manifest.json: no such
  // file", exit 11); on motifs.json it is a usage error, not damage (it said "bad magic", 12).
  const RunResult folder = RunTool("verify " + dir.File("out"));
  EXPECT_EQ(folder.exit_code, 0) << folder.output;
  EXPECT_NE(folder.output.find("a mine output folder: " + dir.File("s.mfs") + ", trellis.mtr"),
            std::string::npos)
      << folder.output;
  EXPECT_NE(folder.output.find("motifs.json ("), std::string::npos) << folder.output;
  const RunResult json = RunTool("verify " + dir.File("out/motifs.json"));
  EXPECT_EQ(json.exit_code, 2) << json.output;
  EXPECT_NE(json.output.find("motifs.json is not an archive (.mfs), trellis (.mtr)"),
            std::string::npos)
      << json.output;
  std::filesystem::copy_file(dir.File("out/trellis.mtr"), dir.File("trellis.copy"));
  EXPECT_NE(RunTool("verify " + dir.File("trellis.copy")).output.find("columns"),
            std::string::npos);  // known by its bytes, whatever its name
}

// No debug lines by default: the LSH index's parameters only with --verbose.
TEST(MotifmineTool, TheSearchIndexParametersPrintOnlyWithVerbose) {
  testing::TempDir dir;
  const std::string archive = dir.File("s.mfs");
  ASSERT_EQ(RunTool("synth " + archive + " --frames 6000 --motifs 1 --seed 2 --quiet").exit_code, 0);
  const std::string mine = "mine " + archive + " --search lsh --no-report --out ";
  const RunResult plain = RunTool(mine + dir.File("plain"));
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_EQ(plain.output.find("LSH index:"), std::string::npos) << plain.output;
  const RunResult verbose = RunTool(mine + dir.File("verbose") + " --verbose");
  ASSERT_EQ(verbose.exit_code, 0) << verbose.output;
  EXPECT_NE(verbose.output.find("LSH index: lsh embedding="), std::string::npos) << verbose.output;
}

TEST(MotifmineTool, SynthInfoVerifyAndDamage) {
  testing::TempDir dir;
  const std::string archive = dir.File("s.mfs");
  RunResult synth = RunTool("synth " + archive + " --frames 30000 --motifs 3 --seed 5 --quiet");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  ASSERT_TRUE(std::filesystem::exists(dir.File("s.truth.json")));
  auto truth = nlohmann::json::parse(ReadFileToString(dir.File("s.truth.json")).value());
  EXPECT_EQ(truth["frames"], 30000);
  EXPECT_GE(truth["instances"].size(), 9u);

  RunResult info = RunTool("info " + archive + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.output;
  auto json = nlohmann::json::parse(info.output);
  EXPECT_EQ(json["frames"], 30000);
  EXPECT_EQ(json["skeleton"]["family"], "cmu31");
  uint64_t clip_frames = 0;
  for (const auto& clip : json["clips"]) clip_frames += clip["frames"].get<uint64_t>();
  EXPECT_EQ(clip_frames, 30000u);

  RunResult verify = RunTool("verify " + archive + " --quiet");
  EXPECT_EQ(verify.exit_code, 0) << verify.output;
  EXPECT_NE(verify.output.find("OK"), std::string::npos);

  // Refuses to overwrite without --force.
  EXPECT_EQ(RunTool("synth " + archive + " --frames 100 --quiet").exit_code, 13);

  // Flip one byte in the middle of the data: verify exits 12 (corruption) and names the file.
  {
    std::fstream file(archive, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(static_cast<std::streamoff>(std::filesystem::file_size(archive) / 3));
    char byte = 0;
    file.read(&byte, 1);
    file.seekp(static_cast<std::streamoff>(std::filesystem::file_size(archive) / 3));
    byte = static_cast<char>(byte ^ 0x20);
    file.write(&byte, 1);
  }
  RunResult damaged = RunTool("verify " + archive + " --quiet");
  EXPECT_EQ(damaged.exit_code, 12) << damaged.output;
  EXPECT_NE(damaged.output.find("s.mfs"), std::string::npos) << damaged.output;

  RunResult missing = RunTool("info " + dir.File("absent.mfs"));
  EXPECT_EQ(missing.exit_code, 11) << missing.output;
}

// A small archive of two commits: a synthetic one, then one of its clips exported to `take` and
// imported back.
void MakeTwoCommitArchive(const std::string& archive, const std::string& take) {
  ASSERT_EQ(RunTool("synth " + archive + " --frames 6000 --motifs 1 --seed 2 --quiet").exit_code,
            0);
  // Part of the clip: the whole one would be a copy of it, skipped by the import.
  ASSERT_EQ(RunTool("export " + archive + " --clip synth_000000 --end 300 --out " + take).exit_code,
            0);
  ASSERT_EQ(RunTool("import " + archive + " " + take + " --quiet").exit_code, 0);
}

// An archive whose newest commit is damaged (a flipped byte in its footer): no command reads the
// previous version in its place unless --allow-older is given, and none appends to it.
TEST(MotifmineTool, ADamagedNewestCommitIsRefusedUnlessAllowOlder) {
  testing::TempDir dir;
  const std::string archive = dir.File("a.mfs");
  const std::string take = dir.File("t.bvh");
  ASSERT_NO_FATAL_FAILURE(MakeTwoCommitArchive(archive, take));
  std::string bytes = ReadFileToString(archive).value();
  bytes[bytes.size() - 20] ^= 0x01;  // inside the newest footer
  ASSERT_TRUE(AtomicWriteFile(archive, bytes).ok());

  for (const std::string& command :
       {"info " + archive, "mine " + archive + " --out " + dir.File("m") + " --quiet --no-report",
        "export " + archive + " --clip synth_000000 --out " + dir.File("x.bvh")}) {
    const RunResult refused = RunTool(command);
    EXPECT_EQ(refused.exit_code, 12) << command << "\n" << refused.output;
    EXPECT_NE(refused.output.find("footer checksum mismatch"), std::string::npos) << refused.output;
    EXPECT_NE(refused.output.find("--allow-older"), std::string::npos) << refused.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.File("m/motifs.json")));
  EXPECT_FALSE(std::filesystem::exists(dir.File("x.bvh")));

  const RunResult older = RunTool("info " + archive + " --json --allow-older");
  ASSERT_EQ(older.exit_code, 0) << older.output;
  EXPECT_NE(older.output.find("warning: "), std::string::npos) << older.output;
  EXPECT_NE(older.output.find("generation 1"), std::string::npos) << older.output;
  EXPECT_EQ(RunTool("verify " + archive + " --quiet").exit_code, 12);

  // No append over the damaged version: the file stays byte for byte.
  const RunResult import = RunTool("import " + archive + " " + take + " --allow-older --quiet");
  EXPECT_EQ(import.exit_code, 12) << import.output;
  EXPECT_EQ(ReadFileToString(archive).value(), bytes);
}

// A flipped bit in the commit slot that names the newest version (bytes 0x58-0x7f of a
// two-commit archive): the version is read from its footer, verify reports the slot, and the
// next import keeps every clip.
TEST(MotifmineTool, AFlippedBitInTheActiveCommitSlotLosesNothing) {
  testing::TempDir dir;
  const std::string archive = dir.File("a.mfs");
  const std::string take = dir.File("t.bvh");
  ASSERT_NO_FATAL_FAILURE(MakeTwoCommitArchive(archive, take));
  std::string bytes = ReadFileToString(archive).value();
  bytes[0x60] ^= 0x10;
  ASSERT_TRUE(AtomicWriteFile(archive, bytes).ok());

  const RunResult verify = RunTool("verify " + archive + " --quiet");
  EXPECT_EQ(verify.exit_code, 12) << verify.output;
  EXPECT_NE(verify.output.find("commit slot 1"), std::string::npos) << verify.output;
  const RunResult info = RunTool("info " + archive + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_EQ(nlohmann::json::parse(info.output)["clips"].size(), 3u);

  const std::string second = dir.File("u.bvh");
  ASSERT_EQ(RunTool("export " + archive + " --clip synth_000001 --end 200 --out " + second).exit_code,
            0);
  const RunResult import = RunTool("import " + archive + " " + second + " --quiet");
  ASSERT_EQ(import.exit_code, 0) << import.output;
  EXPECT_EQ(nlohmann::json::parse(RunTool("info " + archive + " --json").output)["clips"].size(),
            4u);
  EXPECT_EQ(RunTool("verify " + archive + " --quiet").exit_code, 0);
}

// A missing input leaves no output folder behind, and an output in a missing folder names the
// folder, not the temporary file that could not be made.
TEST(MotifmineTool, AMissingInputOrOutputFolderIsNamedAndLeavesNothing) {
  testing::TempDir dir;
  const RunResult mine =
      RunTool("mine " + dir.File("nosuch/") + " --out " + dir.File("out") + " --quiet");
  EXPECT_EQ(mine.exit_code, 11) << mine.output;
  EXPECT_NE(mine.output.find(dir.File("nosuch/") + ": no such file or folder"), std::string::npos)
      << mine.output;
  EXPECT_FALSE(std::filesystem::exists(dir.File("out")));

  const std::string archive = dir.File("s.mfs");
  ASSERT_EQ(RunTool("synth " + archive + " --frames 6000 --motifs 1 --seed 2 --quiet").exit_code,
            0);
  const RunResult exported =
      RunTool("export " + archive + " --clip synth_000000 --out " + dir.File("missing/x.bvh"));
  EXPECT_EQ(exported.exit_code, 14) << exported.output;
  EXPECT_NE(exported.output.find(dir.File("missing") + " does not exist"), std::string::npos)
      << exported.output;
  EXPECT_EQ(exported.output.find(".tmp-"), std::string::npos) << exported.output;

  ASSERT_EQ(RunTool("export " + archive + " --clip synth_000000 --end 300 --out " +
                    dir.File("take.bvh")).exit_code, 0);
  const RunResult imported =
      RunTool("import " + dir.File("missing/a.mfs") + " " + dir.File("take.bvh") + " --quiet");
  EXPECT_EQ(imported.exit_code, 14) << imported.output;
  EXPECT_NE(imported.output.find(dir.File("missing/a.mfs") + ": cannot create the archive: the "
                                 "folder " + dir.File("missing") + " does not exist"),
            std::string::npos) << imported.output;
  EXPECT_EQ(imported.output.find(".tmp-"), std::string::npos) << imported.output;
  EXPECT_FALSE(std::filesystem::exists(dir.File("missing")));
}

// A folder that cannot be made is an I/O error (exit 14) naming it; a disk too full for an
// append is exit 16 naming the archive, which stays as it was (a real full tmpfs, when the test
// may mount one).
TEST(MotifmineTool, AnIoErrorAndAFullDiskHaveTheirExitCodes) {
  testing::TempDir dir;
  const std::string archive = dir.File("a.mfs");
  const std::string take = dir.File("t.bvh");
  ASSERT_NO_FATAL_FAILURE(MakeTwoCommitArchive(archive, take));
  ASSERT_TRUE(AtomicWriteFile(dir.File("plain"), "x").ok());
  const RunResult io =
      RunTool("mine " + archive + " --out " + dir.File("plain/out") + " --quiet --no-report");
  EXPECT_EQ(io.exit_code, 14) << io.output;
  EXPECT_NE(io.output.find("cannot create " + dir.File("plain/out")), std::string::npos)
      << io.output;

  testing::Tmpfs tmpfs(dir.File("small"));
  if (!tmpfs.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here (not root?): no full disk";
  const std::string small = dir.File("small/a.mfs");
  std::filesystem::copy_file(archive, small);
  const std::string before = ReadFileToString(small).value();
  const std::string other = dir.File("u.bvh");  // content not yet in the archive
  ASSERT_EQ(
      RunTool("export " + archive + " --clip synth_000000 --start 10 --out " + other).exit_code, 0);
  ASSERT_TRUE(tmpfs.LeaveRoom(16 << 10));
  const RunResult full = RunTool("import " + small + " " + other + " --quiet");
  EXPECT_EQ(full.exit_code, 16) << full.output;
  EXPECT_NE(full.output.find(small), std::string::npos) << full.output;
  EXPECT_NE(full.output.find("No space left on device"), std::string::npos) << full.output;
  EXPECT_EQ(ReadFileToString(small).value(), before);
  EXPECT_EQ(RunTool("verify " + small + " --quiet").exit_code, 0);
}

// A file of a newer format major version is not supported (exit 15), not damaged (12).
TEST(MotifmineTool, ANewerFormatVersionIsNotSupported) {
  testing::TempDir dir;
  const std::string archive = dir.File("a.mfs");
  ASSERT_EQ(RunTool("synth " + archive + " --frames 6000 --motifs 1 --seed 2 --quiet").exit_code,
            0);
  std::string bytes = ReadFileToString(archive).value();
  bytes[8] = 2;  // format_major, checked before the header checksum
  ASSERT_TRUE(AtomicWriteFile(archive, bytes).ok());
  for (const std::string& command : {"verify " + archive, "info " + archive}) {
    const RunResult result = RunTool(command);
    EXPECT_EQ(result.exit_code, 15) << command << "\n" << result.output;
    EXPECT_NE(result.output.find("unsupported format major version 2"), std::string::npos)
        << result.output;
  }
}

// --skip-bad: the good takes are stored and mined, each bad one is named on stderr even under
// --quiet, and the exit code is 3 (done, with warnings).
TEST(MotifmineTool, SkipBadStoresTheGoodTakesNamesTheBadOnesAndExitsThree) {
  testing::TempDir dir;
  const std::string synth = dir.File("s.mfs");
  ASSERT_EQ(RunTool("synth " + synth + " --frames 6000 --motifs 1 --seed 2 --quiet").exit_code, 0);
  std::filesystem::create_directories(dir.File("takes"));
  ASSERT_EQ(RunTool("export " + synth + " --clip synth_000000 --out " + dir.File("takes/good.bvh"))
                .exit_code,
            0);
  const std::string bad = dir.File("takes/bad.bvh");
  ASSERT_TRUE(AtomicWriteFile(bad, "garbage\n").ok());
  // A root position of 1e308 (a parsed take whose velocity is not finite) and an AMC take with no
  // ASF to pair fail alone too.
  std::string text = ReadFileToString(dir.File("takes/good.bvh")).value();
  const size_t first_frame = text.find('\n', text.find("Frame Time:")) + 1;
  text.replace(first_frame, text.find(' ', first_frame) - first_frame, "1e308");
  const std::string huge = dir.File("takes/huge.bvh");
  ASSERT_TRUE(AtomicWriteFile(huge, text).ok());
  const std::string lonely = dir.File("takes/lonely.amc");
  ASSERT_TRUE(AtomicWriteFile(lonely, ":FULLY-SPECIFIED\n:DEGREES\n").ok());

  const std::string archive = dir.File("a.mfs");
  const RunResult import =
      RunTool("import " + archive + " " + dir.File("takes") + " --skip-bad --quiet");
  EXPECT_EQ(import.exit_code, 3) << import.output;
  for (const std::string& file : {bad, huge, lonely}) {
    EXPECT_NE(import.output.find("skipped: " + file), std::string::npos) << import.output;
  }
  const RunResult info = RunTool("info " + archive + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_EQ(nlohmann::json::parse(info.output)["clips"].size(), 1u);

  const RunResult mine = RunTool("mine " + dir.File("takes") + " --out " + dir.File("m") +
                                 " --skip-bad --quiet --no-report");
  EXPECT_EQ(mine.exit_code, 3) << mine.output;
  EXPECT_NE(mine.output.find("skipped: " + bad), std::string::npos) << mine.output;
  // Counts read as words do (one clip, three takes), the rate as a number.
  EXPECT_NE(mine.output.find(" at 120 fps) in 1 clip\n"), std::string::npos) << mine.output;
  EXPECT_NE(mine.output.find("skipped      3 bad takes"), std::string::npos) << mine.output;
  EXPECT_TRUE(std::filesystem::exists(dir.File("m/motifs.json")));
  // Without --skip-bad one bad take stops the import, and nothing is stored.
  EXPECT_EQ(RunTool("import " + dir.File("b.mfs") + " " + dir.File("takes") + " --quiet").exit_code,
            13);
  EXPECT_FALSE(std::filesystem::exists(dir.File("b.mfs")));
}

// Take descriptions from an index the user gives: import and mine keep them in the archive's
// clips, info lists them, the report shows them beside the take's name; a malformed index is
// refused by name before anything is written.
TEST(MotifmineTool, TakeDescriptionsFromAnIndexReachInfoAndTheReport) {
  testing::TempDir dir;
  const std::string synth = dir.File("s.mfs");
  ASSERT_EQ(RunTool("synth " + synth + " --frames 6000 --motifs 1 --seed 2 --quiet").exit_code, 0);
  std::filesystem::create_directories(dir.File("takes"));
  for (const char* clip : {"synth_000000", "synth_000001"}) {
    ASSERT_EQ(RunTool("export " + synth + " --clip " + clip + " --out " +
                      dir.File(std::string("takes/") + clip + ".bvh"))
                  .exit_code,
              0);
  }
  const std::string index = dir.File("index.tsv");
  ASSERT_TRUE(AtomicWriteFile(index,
                              "file\tdescription\n"
                              "takes/synth_000000.bvh\tjumping <jacks> & claps\n")
                  .ok());
  const std::string archive = dir.File("a.mfs");
  const RunResult import = RunTool("import " + archive + " " + dir.File("takes") +
                                   " --descriptions " + index + " --quiet");
  ASSERT_EQ(import.exit_code, 0) << import.output;
  const nlohmann::json clips =
      nlohmann::json::parse(RunTool("info " + archive + " --json").output)["clips"];
  ASSERT_EQ(clips.size(), 2u);
  EXPECT_EQ(clips[0]["description"], "jumping <jacks> & claps");
  EXPECT_FALSE(clips[1].contains("description"));

  const RunResult mine = RunTool("mine " + dir.File("takes") + " --descriptions " + index +
                                 " --out " + dir.File("m") + " --playback-mb 0 --quiet");
  ASSERT_EQ(mine.exit_code, 0) << mine.output;
  const std::string html = ReadFileToString(dir.File("m/report.html")).value();
  EXPECT_NE(html.find("synth_000000<small> \u2014 jumping &lt;jacks&gt; &amp; claps</small>"),
            std::string::npos);
  // The overview's length as a person writes it (it said "0.8 min").
  EXPECT_NE(html.find("6,000 (50.0 s at 120 fps)"), std::string::npos);
  // mine --playback-mb 0 passes to the report: no player data in the page.
  EXPECT_EQ(html.find("id=\"play-figure\""), std::string::npos);
  EXPECT_NE(html.find("No player in this page"), std::string::npos);
  // A rerun into the same folder with another index: its takes were imported already, and the
  // report shows the new descriptions; `report` run again keeps them (run.json).
  const std::string second = dir.File("second.tsv");
  ASSERT_TRUE(AtomicWriteFile(second, "file\tdescription\nsynth_000000.bvh\twaves\n").ok());
  const RunResult rerun = RunTool("mine " + dir.File("takes") + " --descriptions " + second +
                                  " --out " + dir.File("m") + " --playback-mb 0 --quiet");
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  const std::string described = "synth_000000<small> \u2014 waves</small>";
  EXPECT_NE(ReadFileToString(dir.File("m/report.html")).value().find(described),
            std::string::npos);
  ASSERT_EQ(RunTool("report " + dir.File("m") + " --out " + dir.File("again.html")).exit_code, 0);
  EXPECT_NE(ReadFileToString(dir.File("again.html")).value().find(described), std::string::npos);

  const std::string bad = dir.File("bad.tsv");
  ASSERT_TRUE(AtomicWriteFile(bad, "name\tdescription\nx\ty\n").ok());
  const RunResult refused = RunTool("mine " + dir.File("takes") + " --descriptions " + bad +
                                    " --out " + dir.File("n") + " --quiet");
  EXPECT_EQ(refused.exit_code, 13) << refused.output;
  EXPECT_NE(refused.output.find(bad + ":1"), std::string::npos) << refused.output;
  EXPECT_FALSE(std::filesystem::exists(dir.File("n")));
  EXPECT_EQ(RunTool("import " + dir.File("b.mfs") + " " + dir.File("takes") + " --descriptions " +
                    bad + " --quiet")
                .exit_code,
            13);
  EXPECT_FALSE(std::filesystem::exists(dir.File("b.mfs")));
}

TEST(MotifmineTool, BvhRoundTripKeepsRotationsWithinTheQuantisationBound) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string source = testing::MocapDir() + "/bvh/05_01.bvh";
  testing::TempDir dir;
  const std::string archive = dir.File("r.mfs");
  RunResult imported = RunTool("import " + archive + " " + source + " --quiet");
  ASSERT_EQ(imported.exit_code, 0) << imported.output;
  const std::string exported = dir.File("out.bvh");
  RunResult exported_run = RunTool("export " + archive + " --clip 05_01 --out " + exported);
  ASSERT_EQ(exported_run.exit_code, 0) << exported_run.output;

  ImportOptions options;
  auto original = ImportTake({TakeFormat::kBvh, source, "", ""}, options);
  ASSERT_TRUE(original.ok()) << original.status().ToString();
  options.first_frame = FirstFramePolicy::kKeep;
  auto round_trip = ImportTake({TakeFormat::kBvh, exported, "", ""}, options);
  ASSERT_TRUE(round_trip.ok()) << round_trip.status().ToString();
  ASSERT_EQ(round_trip->frame_count(), original->frame_count());
  // Documented bound (docs/formats/frame_file.md): rotation angle error <= 4 * 2^-15 rad.
  const double bound = 4.0 / 32768.0 + 1e-6;
  double worst = 0;
  for (size_t frame_idx = 0; frame_idx < original->frame_count(); ++frame_idx) {
    for (size_t joint_idx = 0; joint_idx < original->joint_count(); ++joint_idx) {
      worst = std::max(worst, RotationAngleBetween(original->rotation(frame_idx, joint_idx),
                                                   round_trip->rotation(frame_idx, joint_idx)));
    }
    EXPECT_LT((original->root_positions[frame_idx] - round_trip->root_positions[frame_idx]).norm(),
              0.01)
        << "frame " << frame_idx;
  }
  EXPECT_LE(worst, bound);

  // A frame range, and a range outside the clip.
  RunResult range = RunTool("export " + archive + " --clip 05_01 --start 100 --end 220 --out " +
                            dir.File("range.bvh"));
  ASSERT_EQ(range.exit_code, 0) << range.output;
  auto ranged = ImportTake({TakeFormat::kBvh, dir.File("range.bvh"), "", ""}, options);
  ASSERT_TRUE(ranged.ok());
  EXPECT_EQ(ranged->frame_count(), 120u);
  EXPECT_LE(RotationAngleBetween(ranged->rotation(0, 2), original->rotation(100, 2)), bound);
  EXPECT_EQ(RunTool("export " + archive + " --clip 05_01 --start 10 --end 100000 --out " +
                    dir.File("x.bvh"))
                .exit_code,
            13);
  EXPECT_EQ(RunTool("export " + archive + " --clip nope --out " + dir.File("x.bvh")).exit_code, 11);
}

TEST(MotifmineTool, ImportOfMalformedFileNamesFileAndLeavesArchiveUnchanged) {
  MOTIF_REQUIRE_MOCAP_DATA();
  testing::TempDir dir;
  const std::string archive = dir.File("a.mfs");
  ASSERT_EQ(
      RunTool("import " + archive + " " + testing::MocapDir() + "/bvh/02_01.bvh --quiet").exit_code,
      0);
  const std::string before = ReadFileToString(archive).value();
  const std::string bad = dir.File("broken.bvh");
  std::string text = ReadFileToString(testing::MocapDir() + "/bvh/02_02.bvh").value();
  text.resize(text.size() / 2);  // truncated mid-frame
  ASSERT_TRUE(AtomicWriteFile(bad, text).ok());
  RunResult result = RunTool("import " + archive + " " + bad + " --quiet");
  EXPECT_EQ(result.exit_code, 13) << result.output;
  EXPECT_NE(result.output.find("broken.bvh"), std::string::npos) << result.output;
  EXPECT_EQ(ReadFileToString(archive).value(), before);
}

// `score` given a segments.json scores its groups against per-frame labels: three groups for two
// actions are all right by the majority rule, and one-to-one leaves one group's 5 frames
// unscored; a frame with two labels is exit 13 naming it.
TEST(MotifmineTool, ScoreGivenSegmentsScoresGroupsAgainstPerFrameLabels) {
  testing::TempDir dir;
  const std::string segments = dir.File("segments.json");
  std::ofstream(segments) << R"({"version": 1, "mode": "unsupervised", "segments": [
      {"clip": "a", "start": 0, "end": 10, "label": "group 1", "words": 2},
      {"clip": "a", "start": 10, "end": 15, "label": "group 2", "words": 1},
      {"clip": "a", "start": 15, "end": 20, "label": "group 3", "words": 1}]})";
  const std::string labels = dir.File("labels.tsv");
  std::ofstream(labels) << "clip\tmovement\tstart\tend\na\tjump\t0\t10\na\twalk\t10\t20\n";
  const RunResult json = RunTool("score " + segments + " " + labels + " --json");
  ASSERT_EQ(json.exit_code, 0) << json.output;
  const nlohmann::json score = nlohmann::json::parse(json.output);
  EXPECT_EQ(score["frames"], 20);
  EXPECT_DOUBLE_EQ(score["majority"]["accuracy"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(score["one_to_one"]["accuracy"].get<double>(), 0.75);
  EXPECT_EQ(score["groups"].size(), 3u);
  const RunResult text = RunTool("score " + segments + " " + labels);
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("one-to-one   frame accuracy 0.750"), std::string::npos)
      << text.output;
  std::ofstream(labels) << "clip\tmovement\tstart\tend\na\tjump\t0\t10\na\twalk\t9\t20\n";
  const RunResult refused = RunTool("score " + segments + " " + labels);
  EXPECT_EQ(refused.exit_code, 13);
  EXPECT_NE(refused.output.find("frame 9 of clip a carries two labels"), std::string::npos)
      << refused.output;
}

}  // namespace
}  // namespace motif
