#include "engine/ingest/archive_import.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "formats/frame_file/frame_file_reader.h"
#include "tests/testing/mocap_data.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

// A named default: GCC 12 warns (falsely) about uninitialised members of a braced temporary.
const ArchiveImportOptions& DefaultOptions() {
  static const ArchiveImportOptions options;
  return options;
}

// INDEX.tsv: file -> frames (the BVH counts include the converter's T-pose frame).
std::map<std::string, uint64_t> IndexFrames(const std::string& mocap) {
  std::map<std::string, uint64_t> frames;
  std::ifstream index(mocap + "/INDEX.tsv");
  std::string line;
  std::getline(index, line);  // header
  while (std::getline(index, line)) {
    std::istringstream fields(line);
    std::string file, format, subject, trial, count;
    std::getline(fields, file, '\t');
    std::getline(fields, format, '\t');
    std::getline(fields, subject, '\t');
    std::getline(fields, trial, '\t');
    std::getline(fields, count, '\t');
    if (!count.empty()) frames[file] = std::stoull(count);
  }
  return frames;
}

// Expected stored frames for the INDEX entries under `prefix` ("bvh/", "asfamc/").
std::pair<uint64_t, uint64_t> ExpectedClipsAndFrames(const std::string& mocap,
                                                     const std::string& prefix) {
  uint64_t clips = 0;
  uint64_t frames = 0;
  for (const auto& [file, count] : IndexFrames(mocap)) {
    if (file.rfind(prefix, 0) != 0) continue;
    const bool is_bvh = file.size() > 4 && file.substr(file.size() - 4) == ".bvh";
    ++clips;
    frames += is_bvh ? count - 1 : count;  // cgspeed BVH: the T-pose frame is dropped
  }
  return {clips, frames};
}

TEST(ImportIntoArchive, RealBvhAndAsfAmcArchivesHaveTheIndexedClipsAndFrames) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string mocap = testing::MocapDir();
  testing::TempDir dir;
  struct Case {
    std::vector<std::string> folders;
    std::vector<std::string> prefixes;
    std::string family;
    std::vector<std::string> copies;  // INDEX files skipped as copies of a BVH take (their frames)
  };
  // Six AMC takes are the captures of BVH takes (the same frames in another format).
  const std::vector<std::string> amc_copies = {
      "asfamc/05/05_01.amc", "asfamc/05/05_02.amc",      "asfamc/05/05_03.amc",
      "asfamc/05/05_16.amc", "asfamc/07/07_05-walk.amc", "asfamc/09/09_06-run.amc"};
  const Case cases[] = {
      {{mocap + "/bvh"}, {"bvh/"}, "cmu31", {}},
      {{mocap + "/asfamc"}, {"asfamc/"}, "cmu31", {}},
      {{mocap + "/bvh", mocap + "/asfamc"}, {"bvh/", "asfamc/"}, "cmu31", amc_copies},
      {{mocap + "/bvh_daz"}, {"bvh_daz/"}, "custom", {}},
  };
  int case_idx = 0;
  for (const Case& test_case : cases) {
    const std::string archive = dir.File("case" + std::to_string(case_idx++) + ".mfs");
    auto result = ImportIntoArchive(archive, test_case.folders, DefaultOptions());
    ASSERT_TRUE(result.ok()) << result.status().ToString();
    uint64_t clips = 0;
    uint64_t frames = 0;
    for (const std::string& prefix : test_case.prefixes) {
      auto [prefix_clips, prefix_frames] = ExpectedClipsAndFrames(mocap, prefix);
      clips += prefix_clips;
      frames += prefix_frames;
    }
    for (const std::string& copy : test_case.copies) {
      ASSERT_TRUE(IndexFrames(mocap).count(copy)) << copy;
      clips -= 1;
      frames -= IndexFrames(mocap).at(copy);
    }
    auto reader = FrameFileReader::Open(archive);
    ASSERT_TRUE(reader.ok()) << reader.status().ToString();
    EXPECT_EQ((*reader)->clips().size(), clips) << archive;
    EXPECT_EQ((*reader)->frame_count(), frames) << archive;
    EXPECT_EQ((*reader)->skeleton().family(), test_case.family);
    EXPECT_EQ((*reader)->fps(), 120.0);
    EXPECT_TRUE((*reader)->Verify().ok());
  }
}

// A folder of several families makes an archive on the CMU body, whichever take comes first;
// a later take of another family is mapped onto it too. The notes say so, once per skeleton.
TEST(ImportIntoArchive, MixedFamiliesAreMappedOntoTheCmuBody) {
  MOTIF_REQUIRE_MOCAP_DATA();
  MOTIF_REQUIRE_STUDIO_RIG_DATA();
  const std::string mocap = testing::MocapDir();
  const std::string rig = testing::StudioRigDir() + "/bvh/dataset-2_walk_normal_001.bvh";
  testing::TempDir dir;
  const std::string archive = dir.File("mixed.mfs");
  std::vector<std::string> notes;
  ArchiveImportOptions options;
  options.note = [&](const std::string& note) { notes.push_back(note); };
  auto result = ImportIntoArchive(
      archive, {rig, mocap + "/bvh/02_02.bvh", mocap + "/bvh_daz/02_01.bvh", mocap + "/bvh_daz/12_01.bvh"},
      options);
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  EXPECT_EQ(result->takes_imported, 4u);
  EXPECT_EQ(result->takes_mapped, 3u);
  auto reader = FrameFileReader::Open(archive);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  EXPECT_EQ((*reader)->skeleton().family(), "cmu31");
  EXPECT_EQ((*reader)->skeleton().joint_count(), 31u);
  EXPECT_TRUE((*reader)->Verify().ok());
  const auto noted = [&](const std::string& text) {
    return std::count_if(notes.begin(), notes.end(), [&](const std::string& note) {
      return note.find(text) != std::string::npos;
    });
  };
  EXPECT_EQ(noted("the takes are of several skeleton families, each mapped onto the CMU body"), 1);
  EXPECT_EQ(noted("a 21-joint skeleton (root 'Hips'), mapped onto the CMU body"), 1);
  EXPECT_EQ(noted("a 43-joint skeleton (root 'hip'), mapped onto the CMU body"), 1);

  auto appended = ImportIntoArchive(archive, {mocap + "/bvh_daz/13_11.bvh"}, options);
  ASSERT_TRUE(appended.ok()) << appended.status().ToString();
  EXPECT_EQ(appended->takes_mapped, 1u);
  EXPECT_EQ(appended->archive_clips, 5u);
}

// An archive of another family holds its own skeleton alone: a CMU take is refused, the
// message says what an archive holds and which option lets the other takes in.
TEST(ImportIntoArchive, AnArchiveOfAnotherFamilyRefusesOtherSkeletonsAndNothingIsStored) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string mocap = testing::MocapDir();
  testing::TempDir dir;
  const std::string archive = dir.File("daz.mfs");
  ASSERT_TRUE(ImportIntoArchive(archive, {mocap + "/bvh_daz/02_01.bvh"}, DefaultOptions()).ok());
  const std::string before = ReadFileToString(archive).value();
  auto result = ImportIntoArchive(archive, {mocap + "/bvh_daz/12_01.bvh", mocap + "/bvh/02_02.bvh"},
                                  DefaultOptions());
  ASSERT_FALSE(result.ok());
  EXPECT_TRUE(result.status().IsInvalidArgument()) << result.status().ToString();
  EXPECT_NE(result.status().message().find("bvh/02_02.bvh"), std::string::npos)
      << result.status().message();
  EXPECT_NE(result.status().message().find("an archive holds one skeleton family, and one made "
                                           "from a folder of several is on the CMU body; "
                                           "skip_bad imports the other takes"),
            std::string::npos)
      << result.status().message();
  EXPECT_EQ(result.status().option(), "skip_bad");
  EXPECT_EQ(ReadFileToString(archive).value(), before) << "the archive was changed";
}

TEST(ImportIntoArchive, ReimportSkipsKnownTakesAndRenamesClashingStems) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string mocap = testing::MocapDir();
  testing::TempDir dir;
  const std::string archive = dir.File("a.mfs");
  ASSERT_TRUE(ImportIntoArchive(archive, {mocap + "/bvh/05_01.bvh"}, DefaultOptions()).ok());
  const std::string before = ReadFileToString(archive).value();
  auto again = ImportIntoArchive(archive, {mocap + "/bvh/05_01.bvh"}, DefaultOptions());
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->takes_imported, 0u);
  EXPECT_EQ(again->takes_already_present, 1u);
  // Nothing added, nothing committed: the same bytes, so the same generation and identity.
  EXPECT_EQ(ReadFileToString(archive).value(), before);
  // The AMC of the same take has other bytes and the same frames: a copy, skipped.
  auto amc = ImportIntoArchive(archive, {mocap + "/asfamc/05/05_01.amc"}, DefaultOptions());
  ASSERT_TRUE(amc.ok()) << amc.status().ToString();
  EXPECT_EQ(amc->takes_imported, 0u);
  EXPECT_EQ(amc->takes_already_present, 1u);
  // Another take of the same stem: stored under another name.
  std::filesystem::create_directories(dir.File("other"));
  std::filesystem::copy_file(mocap + "/bvh/05_02.bvh", dir.File("other/05_01.bvh"));
  auto same_stem = ImportIntoArchive(archive, {dir.File("other/05_01.bvh")}, DefaultOptions());
  ASSERT_TRUE(same_stem.ok()) << same_stem.status().ToString();
  EXPECT_EQ(same_stem->takes_imported, 1u);
  auto reader = FrameFileReader::Open(archive);
  ASSERT_TRUE(reader.ok());
  ASSERT_EQ((*reader)->clips().size(), 2u);
  EXPECT_EQ((*reader)->clips()[0].name, "05_01");
  EXPECT_EQ((*reader)->clips()[1].name, "05_01~2");
}

TEST(ImportIntoArchive, AMalformedTakeStopsTheImportUnlessSkipped) {
  testing::TempDir dir;
  const std::string good = dir.File("good.bvh");
  const std::string bad = dir.File("bad.bvh");
  const std::string header =
      "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition "
      "Zrotation Yrotation Xrotation\n JOINT Leg\n {\n  OFFSET 0 -1 0\n  CHANNELS 3 Zrotation "
      "Xrotation Yrotation\n  End Site\n  {\n   OFFSET 0 -1 0\n  }\n }\n}\nMOTION\n";
  std::string good_text = header + "Frames: 3\nFrame Time: 0.0333333\n";
  for (int frame = 0; frame < 3; ++frame) good_text += "0 1 0 0 0 0 10 0 0\n";
  ASSERT_TRUE(AtomicWriteFile(good, good_text).ok());
  ASSERT_TRUE(AtomicWriteFile(bad, header + "Frames: 2\nFrame Time: 0.0333333\n0 1 0 0 0 0 10 0\n"
                                            "0 1 0 0 0 0 10 0 0\n")
                  .ok());
  ArchiveImportOptions options;
  options.import.first_frame = FirstFramePolicy::kKeep;
  const std::string archive = dir.File("x.mfs");
  auto failed = ImportIntoArchive(archive, {dir.path()}, options);
  ASSERT_FALSE(failed.ok());
  EXPECT_NE(failed.status().message().find("bad.bvh"), std::string::npos);
  EXPECT_NE(failed.status().message().find("(skip_bad imports the other takes)"),
            std::string::npos)
      << failed.status().message();
  EXPECT_EQ(failed.status().option(), "skip_bad");  // the tool says --skip-bad
  EXPECT_FALSE(std::filesystem::exists(archive));
  options.skip_bad = true;
  auto skipped = ImportIntoArchive(archive, {dir.path()}, options);
  ASSERT_TRUE(skipped.ok()) << skipped.status().ToString();
  EXPECT_EQ(skipped->takes_imported, 1u);
  EXPECT_EQ(skipped->takes_failed, 1u);
  EXPECT_EQ(skipped->archive_frames, 3u);
}

// A two-joint BVH take of `frames` frames at `fps`.
std::string TwoJointTake(int frames, double fps) {
  std::string text =
      "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition "
      "Zrotation Yrotation Xrotation\n JOINT Leg\n {\n  OFFSET 0 -1 0\n  CHANNELS 3 Zrotation "
      "Xrotation Yrotation\n  End Site\n  {\n   OFFSET 0 -1 0\n  }\n }\n}\nMOTION\n";
  text += "Frames: " + std::to_string(frames) + "\nFrame Time: " + std::to_string(1.0 / fps) +
          "\n";
  for (int frame = 0; frame < frames; ++frame) {
    text += std::to_string(0.01 * frame) + " 1 0 0 0 0 " + std::to_string(frame % 30) + " 0 0\n";
  }
  return text;
}

TEST(ImportIntoArchive, ATakeReplacedWhileTheArchiveIsCreatedIsImportedAsFirstRead) {
  testing::TempDir dir;
  const std::string take = dir.File("walk.bvh");
  ASSERT_TRUE(AtomicWriteFile(take, TwoJointTake(40, 60.0)).ok());
  ArchiveImportOptions options;
  options.import.first_frame = FirstFramePolicy::kKeep;
  // Between creating the archive (from the take's rate and skeleton) and appending its frames,
  // the take becomes another one at twice the rate.
  options.note = [&](const std::string& message) {
    if (message.rfind("creating ", 0) == 0) {
      ASSERT_TRUE(AtomicWriteFile(take, TwoJointTake(295, 120.0)).ok());
    }
  };
  auto result = ImportIntoArchive(dir.File("a.mfs"), {take}, options);
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  EXPECT_EQ(result->fps, 60.0);
  EXPECT_EQ(result->archive_frames, 40u) << "the take was read twice";
}

TEST(ImportIntoArchive, TheSameFramesInOtherBytesAreSkippedNamingBothTakes) {
  testing::TempDir dir;
  const std::string take = TwoJointTake(90, 120.0);
  std::string reformatted = take;  // the same numbers, written otherwise: other bytes
  for (size_t at = reformatted.find(" 1 0 0 0 0 "); at != std::string::npos;
       at = reformatted.find(" 1 0 0 0 0 ", at + 14)) {
    reformatted.replace(at, 11, " 1.0 0 0 0 0 ");
  }
  std::string other = take;  // one frame's leg turned by 5 degrees more: another take
  other.replace(other.rfind(" 0 0\n"), 5, " 5 0\n");
  ASSERT_TRUE(AtomicWriteFile(dir.File("a.bvh"), take).ok());
  ASSERT_TRUE(AtomicWriteFile(dir.File("b.bvh"), reformatted).ok());
  ASSERT_TRUE(AtomicWriteFile(dir.File("c.bvh"), other).ok());
  std::vector<std::string> notes;
  ArchiveImportOptions options;
  options.import.first_frame = FirstFramePolicy::kKeep;
  options.note = [&](const std::string& note) { notes.push_back(note); };
  // In one import, and against a stored clip in a second one.
  auto first = ImportIntoArchive(dir.File("x.mfs"), {dir.File("a.bvh"), dir.File("b.bvh")}, options);
  ASSERT_TRUE(first.ok()) << first.status().ToString();
  EXPECT_EQ(first->takes_imported, 1u);
  EXPECT_EQ(first->takes_already_present, 1u);
  const std::string expected =
      dir.File("b.bvh") + ": the same frames as clip 'a' (" + dir.File("a.bvh") + "), skipped";
  EXPECT_NE(std::find(notes.begin(), notes.end(), expected), notes.end()) << notes.back();
  auto second = ImportIntoArchive(dir.File("y.mfs"), {dir.File("a.bvh")}, options);
  ASSERT_TRUE(second.ok());
  auto again = ImportIntoArchive(dir.File("y.mfs"), {dir.File("b.bvh"), dir.File("c.bvh")}, options);
  ASSERT_TRUE(again.ok()) << again.status().ToString();
  EXPECT_EQ(again->takes_already_present, 1u);
  EXPECT_EQ(again->takes_imported, 1u) << "c differs in one frame: not a copy";
  EXPECT_EQ(again->archive_clips, 2u);
}

TEST(ImportIntoArchive, SameArchiveBytesWithOneOrTwoThreads) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string mocap = testing::MocapDir();
  testing::TempDir dir;
  std::string bytes[2];
  for (int threads = 1; threads <= 2; ++threads) {
    ArchiveImportOptions options;
    options.threads = threads;
    const std::string archive = dir.File("t" + std::to_string(threads) + ".mfs");
    ASSERT_TRUE(
        ImportIntoArchive(archive, {mocap + "/asfamc/60", mocap + "/asfamc/61"}, options).ok());
    bytes[threads - 1] = ReadFileToString(archive).value();
  }
  EXPECT_EQ(bytes[0], bytes[1]);
}

}  // namespace
}  // namespace motif
