// Malformed input: every damaged BVH, ASF or AMC text gives InvalidArgument naming the file, the
// line and the problem, never a crash; random bytes and random mutations of valid files give
// either a sound take or a clean error.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "formats/import/amc_parser.h"
#include "formats/import/asf_parser.h"
#include "formats/import/bvh_parser.h"
#include "tests/formats/import/import_test_util.h"

namespace motif {
namespace {

using import_test::FixturePath;
using import_test::ReadText;

// Line numbers in the comments are the ones the cases below refer to.
const char kValidBvh[] =
    "HIERARCHY\n"                                                                 // 1
    "ROOT hips\n"                                                                 // 2
    "{\n"                                                                         // 3
    "  OFFSET 0 0 0\n"                                                            // 4
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"  // 5
    "  JOINT chest\n"                                                             // 6
    "  {\n"                                                                       // 7
    "    OFFSET 0 1 0\n"                                                          // 8
    "    CHANNELS 3 Zrotation Yrotation Xrotation\n"                              // 9
    "    End Site\n"                                                              // 10
    "    {\n"                                                                     // 11
    "      OFFSET 0 1 0\n"                                                        // 12
    "    }\n"                                                                     // 13
    "  }\n"                                                                       // 14
    "}\n"                                                                         // 15
    "MOTION\n"                                                                    // 16
    "Frames: 2\n"                                                                 // 17
    "Frame Time: 0.01\n"                                                          // 18
    "1 2 3 4 5 6 7 8 9\n"                                                         // 19
    "1 2 3 4 5 6 7 8 9\n";                                                        // 20

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

// Text up to and including line `line_count`.
std::string FirstLines(const std::string& text, int line_count) {
  size_t pos = 0;
  for (int line = 0; line < line_count; ++line) pos = text.find('\n', pos) + 1;
  return text.substr(0, pos);
}

struct Case {
  const char* name;
  std::string text;
  std::string expected;  // a substring of the message, starting with "<file>:<line>: "
};

void ExpectFailure(const Status& status, const Case& test_case) {
  ASSERT_FALSE(status.ok()) << test_case.name;
  EXPECT_TRUE(status.IsInvalidArgument()) << test_case.name << ": " << status.ToString();
  EXPECT_NE(status.message().find(test_case.expected), std::string::npos)
      << test_case.name << ": got \"" << status.message() << "\", expected \"" << test_case.expected
      << "\"";
}

TEST(MalformedBvh, ValidBaseParses) {
  Result<Take> take = ParseBvh(kValidBvh, "bad.bvh");
  ASSERT_TRUE(take.ok()) << take.status().ToString();
  EXPECT_EQ(take->frame_count(), 2u);
}

TEST(MalformedBvh, ErrorsNameFileLineAndProblem) {
  const std::string valid = kValidBvh;
  const std::vector<Case> cases = {
      {"empty", "", "bad.bvh:1: empty file"},
      {"binary garbage",
       std::string("\x7f"
                   "ELF\x02\x01\x00\x00\x13\x37",
                   10),
       "bad.bvh:1: expected HIERARCHY, found '\\x7fELF\\x02\\x01\\x00\\x00\\x137'"},
      {"no root", "HIERARCHY\nJOINT x\n", "bad.bvh:2: expected ROOT, found 'JOINT'"},
      {"truncated in hierarchy", FirstLines(valid, 9),
       "bad.bvh:9: file ends inside joint 'chest' (opened at line 6)"},
      {"truncated in offset", FirstLines(valid, 3) + "  OFFSET 0 0",
       "bad.bvh:4: file ends inside the OFFSET of joint 'hips'"},
      {"missing MOTION", FirstLines(valid, 15), "bad.bvh:15: missing MOTION section"},
      {"truncated before frames", FirstLines(valid, 17),
       "bad.bvh:17: file ends after 'Frames:': expected 'Frame Time:'"},
      {"truncated frames", FirstLines(valid, 19),
       "bad.bvh:19: file ends after 1 of the 2 frames declared at line 17"},
      {"truncated mid-frame", FirstLines(valid, 19) + "1 2 3 4",
       "bad.bvh:20: frame 1 has 4 values, the hierarchy declares 9 channels"},
      {"too few values",
       Replace(valid, "1 2 3 4 5 6 7 8 9\n1 2 3 4 5 6 7 8 9\n",
               "1 2 3 4 5 6 7 8 9\n1 2 3 4 5 6 7 8\n"),
       "bad.bvh:20: frame 1 has 8 values, the hierarchy declares 9 channels"},
      {"too many values", Replace(valid, "1 2 3 4 5 6 7 8 9\n", "1 2 3 4 5 6 7 8 9 10 11\n"),
       "bad.bvh:19: frame 0 has 11 values, the hierarchy declares 9 channels"},
      {"extra frame line", valid + "1 2 3 4 5 6 7 8 9\n",
       "bad.bvh:21: more frame lines than the 2 declared by 'Frames:' at line 17"},
      {"nan value", Replace(valid, "1 2 3 4 5 6 7 8 9\n", "1 2 nan 4 5 6 7 8 9\n"),
       "bad.bvh:19: frame 0, value 3: 'nan' is not a finite number"},
      {"inf value", Replace(valid, "1 2 3 4 5 6 7 8 9\n", "1 2 3 4 5 -inf 7 8 9\n"),
       "bad.bvh:19: frame 0, value 6: '-inf' is not a finite number"},
      {"overflowing value", Replace(valid, "1 2 3 4 5 6 7 8 9\n", "1 2 3 4 5 6 7 8 1e999\n"),
       "bad.bvh:19: frame 0, value 9: '1e999' is not a finite number"},
      {"absurd rotation", Replace(valid, "1 2 3 4 5 6 7 8 9\n", "1 2 3 4 5 6 7 8 -1e308\n"),
       "bad.bvh:19: frame 0, value 9: a rotation of -1e+308 degrees, beyond the 1e6 degrees a "
       "take can hold"},
      {"word in frame", Replace(valid, "1 2 3 4 5 6 7 8 9\n", "1 2 3 4 5 6 7 8 9x\n"),
       "bad.bvh:19: frame 0, value 9: '9x' is not a finite number"},
      {"nan offset", Replace(valid, "OFFSET 0 1 0", "OFFSET 0 NaN 0"),
       "bad.bvh:8: OFFSET of joint 'chest' needs 3 finite numbers, found 'NaN'"},
      {"channel names short",
       Replace(valid, "Zrotation Yrotation Xrotation\n  JOINT", "Zrotation Yrotation\n  JOINT"),
       "bad.bvh:6: CHANNELS of joint 'hips' declares 6 channels, but 'JOINT' (channel 6) is not "
       "a channel name"},
      {"unknown channel", Replace(valid, "CHANNELS 3 Zrotation", "CHANNELS 3 Wrotation"),
       "bad.bvh:9: CHANNELS of joint 'chest' declares 3 channels, but 'Wrotation' (channel 1)"},
      {"channel twice",
       Replace(valid, "CHANNELS 3 Zrotation Yrotation Xrotation",
               "CHANNELS 3 Zrotation Yrotation Zrotation"),
       "bad.bvh:9: CHANNELS of joint 'chest' lists Zrotation twice"},
      {"channel count", Replace(valid, "CHANNELS 3", "CHANNELS 7"),
       "bad.bvh:9: CHANNELS of joint 'chest' must start with a count from 0 to 6, found '7'"},
      {"missing close brace", Replace(valid, "    }\n  }\n", "    }\n"),
       "bad.bvh:15: MOTION inside joint 'hips' (opened at line 2): unbalanced braces"},
      {"extra close brace", Replace(valid, "}\nMOTION", "}\n}\nMOTION"),
       "bad.bvh:16: unbalanced braces: '}' after the root joint was closed"},
      {"missing offset", Replace(valid, "    OFFSET 0 1 0\n", ""),
       "bad.bvh:13: joint 'chest' has no OFFSET"},
      {"second root", Replace(valid, "MOTION", "ROOT other\n{\n}\nMOTION"),
       "bad.bvh:16: a second ROOT"},
      {"duplicate name", Replace(valid, "JOINT chest", "JOINT hips"),
       "bad.bvh:6: joint name 'hips' is used twice (first at line 2)"},
      {"unknown keyword", Replace(valid, "    End Site", "    Blob"),
       "bad.bvh:10: unexpected 'Blob' in joint 'chest'"},
      {"frames word", Replace(valid, "Frames: 2", "Frames: many"),
       "bad.bvh:17: 'Frames:' needs a non-negative integer, found 'many'"},
      {"negative frames", Replace(valid, "Frames: 2", "Frames: -2"),
       "bad.bvh:17: 'Frames:' needs a non-negative integer, found '-2'"},
      {"zero frames", Replace(valid, "Frames: 2", "Frames: 0"),
       "bad.bvh:17: 'Frames: 0': the take has no frames"},
      {"missing frames line", Replace(valid, "Frames: 2\n", ""),
       "bad.bvh:17: expected 'Frames: <count>', found 'Frame Time: 0.01'"},
      {"missing frame time", Replace(valid, "Frame Time: 0.01\n", ""),
       "bad.bvh:18: expected 'Frame Time: <seconds>', found '1 2 3 4 5 6 7 8 9'"},
      {"negative frame time", Replace(valid, "0.01", "-0.01"),
       "bad.bvh:18: 'Frame Time: -0.01': must be > 0"},
      {"zero frame time", Replace(valid, "0.01", "0"), "bad.bvh:18: 'Frame Time: 0': must be > 0"},
      {"nan frame time", Replace(valid, "0.01", "nan"),
       "bad.bvh:18: 'Frame Time:' needs a finite number, found 'nan'"},
      // Found by fuzzing (tests/data/fuzz/bvh_parser/timeout-frame-time-of-hours.bvh): resampled
      // to 120 fps on import, two frames 38 hours apart became 16 million frames.
      {"frame time of hours", Replace(valid, "0.01", "138300.33"),
       "bad.bvh:18: 'Frame Time: 138300.33': must be between 1e-06 and 1 second (1 to 1000000 "
       "frames per second)"},
      {"frame time below a microsecond", Replace(valid, "0.01", "1e-9"),
       "bad.bvh:18: 'Frame Time: 1e-9': must be between 1e-06 and 1 second"},
      {"huge frame count", Replace(valid, "Frames: 2", "Frames: 99999999999"),
       "bad.bvh:20: file ends after 2 of the 99999999999 frames"},
      {"no channels", "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\n}\nMOTION\nFrames: 1\n",
       "bad.bvh:6: the hierarchy declares no channels"},
  };
  for (const Case& test_case : cases) {
    ExpectFailure(ParseBvh(test_case.text, "bad.bvh").status(), test_case);
  }
}

TEST(MalformedAsf, ErrorsNameFileLineAndProblem) {
  const std::string valid = ReadText(FixturePath("tiny.asf"));
  ASSERT_TRUE(ParseAsf(valid, "bad.asf").ok());
  const std::vector<Case> cases = {
      {"garbage", "\x01\x02garbage\n", "bad.asf:1: expected a ':' section keyword"},
      {"no bonedata", ":version 1.10\n:units\n  length 1\n", "no :bonedata section"},
      {"bad dof", Replace(valid, "dof rx\n", "dof rq\n"),
       "bad.asf:40: bone 'shin' dof: 'rq' is not one of rx ry rz tx ty tz l"},
      {"bad axis order",
       Replace(valid, "axis 0 0 20  XYZ\n    dof rx\n", "axis 0 0 20  XYQ\n    dof rx\n"),
       "bad.asf:39: bone 'shin' axis: the angles must be followed by an order such as XYZ"},
      {"nan direction",
       Replace(valid, "direction 0 -1 0\n     length 5", "direction 0 nan 0\n     length 5"),
       "bad.asf:37: bone 'shin' direction: 'nan' is not a finite number"},
      {"short direction", Replace(valid, "direction 1 0 0", "direction 1 0"),
       "bad.asf:19: bone 'hip' direction needs 3 numbers, found 2"},
      {"unknown field", Replace(valid, "     id 3", "     colour 3"),
       "bad.asf:35: unknown field 'colour' in bone"},
      {"bad length unit", Replace(valid, "length 0.5", "length -1"),
       "bad.asf:6: :units length must be a positive number, found '-1'"},
      {"bad angle unit", Replace(valid, "angle deg", "angle grad"),
       "bad.asf:7: :units angle must be 'deg' or 'rad', found 'grad'"},
      {"bad root order", Replace(valid, "order TX TY TZ RX RY RZ", "order TX TY TZ RX RY RW"),
       "bad.asf:11: :root order: 'RW' is not one of TX TY TZ RX RY RZ"},
      {"unknown hierarchy bone", Replace(valid, "thigh shin", "thigh calf"),
       "bad.asf:58: :hierarchy names an unknown bone 'calf'"},
      {"second parent", Replace(valid, "thigh shin", "thigh shin\n    spine shin"),
       "bad.asf:59: bone 'shin' is given a second parent in :hierarchy"},
      {"unattached bone", Replace(valid, "root hip spine", "root hip"),
       "bad.asf:43: bone 'spine' is not connected to the root in :hierarchy"},
      {"duplicate bone", Replace(valid, "name spine", "name thigh"),
       "bad.asf:43: bone 'thigh' is defined twice"},
      {"truncated in bone", FirstLines(valid, 40),
       "bad.asf:40: file ends inside the bone that begins at line 34"},
      {"truncated hierarchy", FirstLines(valid, 58), "bad.asf:58: :hierarchy has no 'end'"},
      {"section inside bone", Replace(valid, "  end\n:hierarchy", ":hierarchy"),
       "bad.asf:53: :hierarchy inside the bone that begins at line 43 ('end' missing)"},
  };
  for (const Case& test_case : cases) {
    ExpectFailure(ParseAsf(test_case.text, "bad.asf").status(), test_case);
  }
}

TEST(MalformedAmc, ErrorsNameFileLineAndProblem) {
  Result<AsfSkeleton> asf = ParseAsf(ReadText(FixturePath("tiny.asf")), "tiny.asf");
  ASSERT_TRUE(asf.ok()) << asf.status().ToString();
  const std::string valid = ReadText(FixturePath("tiny_01.amc"));
  ASSERT_TRUE(ParseAmc(*asf, valid, "bad.amc", 120).ok());
  const std::vector<Case> cases = {
      {"garbage", std::string("\x89PNG\r\n\x1a\n\0\0", 10),
       "bad.amc:1: expected a frame number before the bone line '\\x89PNG'"},
      {"no frames", ":FULLY-SPECIFIED\n:DEGREES\n", "bad.amc:2: no frames"},
      {"unknown bone", Replace(valid, "shin 45", "lfemur 45"),
       "bad.amc:7: bone 'lfemur' is not in the skeleton tiny.asf"},
      {"too few values", Replace(valid, "thigh -30 5 10", "thigh -30 5"),
       "bad.amc:6: bone 'thigh' has 2 values in frame 1, the ASF gives it 3 dofs (rx ry rz)"},
      {"absurd rotation", Replace(valid, "shin 45", "shin 1e308"),
       "bad.amc:7: bone 'shin', value 1: a rotation beyond the 1e6 degrees a take can hold"},
      {"too many values", Replace(valid, "shin 45", "shin 45 46"),
       "bad.amc:7: bone 'shin' has 2 values in frame 1, the ASF gives it 1 dofs (rx)"},
      {"values for a bone without dof", Replace(valid, "shin 45", "shin 45\nhip 1"),
       "bad.amc:8: bone 'hip' has 1 values in frame 1, the ASF gives it 0 dofs (none)"},
      {"nan value", Replace(valid, "shin 45", "shin NaN"),
       "bad.amc:7: bone 'shin', value 1: 'NaN' is not a finite number"},
      {"bone missing", Replace(valid, "shin 45\n", ""),
       "bad.amc:4: frame 1 has no line for bone 'shin'"},
      {"bone twice", Replace(valid, "shin 45\n", "shin 45\nshin 45\n"),
       "bad.amc:8: bone 'shin' appears twice in frame 1"},
      {"truncated", FirstLines(valid, 11), "bad.amc:9: frame 2 has no line for bone 'thigh'"},
      {"truncated mid-line", FirstLines(valid, 10) + "root 1.5 2",
       "bad.amc:11: bone 'root' has 2 values"},
      {"frame gap", Replace(valid, "\n2\n", "\n3\n"),
       "bad.amc:9: frame number 3 follows frame 1: frame numbers must be consecutive"},
      // Found by fuzzing (tests/data/fuzz/amc_parser/crash-frame-number-overflow.amc): the
      // check computed the largest int64 + 1.
      {"frame after the largest frame number",
       Replace(Replace(valid, "\n1\n", "\n9223372036854775807\n"), "\n2\n",
               "\n-9223372036854775808\n"),
       "bad.amc:9: frame number -9223372036854775808 follows frame 9223372036854775807: frame "
       "numbers must be consecutive"},
      {"frame line with more", Replace(valid, "\n2\n", "\n2 root\n"),
       "bad.amc:9: a frame number line holds only the number, found 'root' after it"},
      {"keyword after frames", valid + ":DEGREES\n",
       "bad.amc:14: ':DEGREES' after the first frame"},
  };
  for (const Case& test_case : cases) {
    ExpectFailure(ParseAmc(*asf, test_case.text, "bad.amc", 120).status(), test_case);
  }
}

// A parsed take must be internally consistent: sizes match and every number is finite.
void ExpectSoundTake(const Take& take) {
  ASSERT_EQ(take.rotations.size(), take.frame_count() * take.joint_count());
  ASSERT_TRUE(take.skeleton.Validate().ok());
  for (const Eigen::Quaterniond& rotation : take.rotations) {
    ASSERT_TRUE(std::isfinite(rotation.w()) && std::isfinite(rotation.x()) &&
                std::isfinite(rotation.y()) && std::isfinite(rotation.z()));
    ASSERT_NEAR(rotation.norm(), 1.0, 1e-9);
  }
  for (const Eigen::Vector3d& position : take.root_positions) ASSERT_TRUE(position.allFinite());
}

void ExpectCleanResult(const Result<Take>& take, const std::string& file_name) {
  if (take.ok()) {
    ExpectSoundTake(*take);
  } else {
    ASSERT_TRUE(take.status().IsInvalidArgument()) << take.status().ToString();
    ASSERT_EQ(take.status().message().rfind(file_name + ":", 0), 0u) << take.status().message();
  }
}

std::string Mutate(const std::string& text, std::mt19937_64* rng) {
  std::string out = text;
  std::uniform_int_distribution<int> kind(0, 7);
  const int mutations = 1 + static_cast<int>((*rng)() % 4);
  for (int idx = 0; idx < mutations && !out.empty(); ++idx) {
    const size_t pos = (*rng)() % out.size();
    switch (kind(*rng)) {
      case 0:
        out[pos] = static_cast<char>((*rng)() & 0xff);
        break;  // random byte
      case 1:
        out.erase(pos, 1 + (*rng)() % 16);
        break;  // delete a run
      case 2:
        out.resize(pos);
        break;  // truncate
      case 3:
        out.insert(out.begin() + pos, " \n\t{}-.e+0123456789"[(*rng)() % 19]);
        break;
      case 4: {
        const std::string_view word = (*rng)() % 2 ? "nan" : "1e400";
        out.insert(out.begin() + pos, word.begin(), word.end());
        break;
      }
      case 5: {  // duplicate a slice (lines, braces, frames)
        const size_t length = std::min<size_t>(1 + (*rng)() % 40, out.size() - pos);
        out.insert(pos, out.substr(pos, length));
        break;
      }
      case 6:
        out[pos] = static_cast<char>('0' + (*rng)() % 10);
        break;  // change a digit
      case 7:
        out.insert(out.begin() + pos, '\r');
        break;
    }
  }
  return out;
}

// A hierarchy deeper than an archive can hold stops the parse where it crosses the limit: the
// parsers used to check every joint name against every other (100,000 BVH joints: 19 s; 100,000
// ASF bones: 44 s) before the writer refused the skeleton.
TEST(MalformedInput, TooManyJointsStopAtTheJointThatCrossesTheLimit) {
  std::string bvh =
      "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n";
  const size_t joints = kMaxSkeletonJoints + 10;
  for (size_t idx = 0; idx < joints; ++idx) {
    bvh += "JOINT j" + std::to_string(idx) + "\n{\nOFFSET 0 1 0\nCHANNELS 1 Zrotation\n";
  }
  bvh += std::string(joints + 1, '}') + "\nMOTION\nFrames: 0\nFrame Time: 0.01\n";
  Result<Take> take = ParseBvh(bvh, "deep.bvh");
  ASSERT_FALSE(take.ok());
  EXPECT_TRUE(take.status().IsInvalidArgument());
  // The root is joint 1 (line 2); joint 4097 opens at line 6 + 4 * 4095.
  EXPECT_EQ(take.status().message(),
            "deep.bvh:" + std::to_string(6 + 4 * (kMaxSkeletonJoints - 1)) +
                ": more than 4096 joints, the most an archive holds");

  std::string asf =
      ":version 1.10\n:name deep\n:units\n  angle deg\n:root\n  order TX TY TZ RX RY RZ\n"
      "  axis XYZ\n  position 0 0 0\n  orientation 0 0 0\n:bonedata\n";
  for (size_t idx = 0; idx < joints; ++idx) {
    asf += "  begin\n    id " + std::to_string(idx + 1) + "\n    name b" + std::to_string(idx) +
           "\n    direction 0 1 0\n    length 1\n    axis 0 0 0 XYZ\n  end\n";
  }
  Result<AsfSkeleton> skeleton = ParseAsf(asf, "deep.asf");
  ASSERT_FALSE(skeleton.ok());
  EXPECT_TRUE(skeleton.status().IsInvalidArgument());
  EXPECT_NE(skeleton.status().message().find("more than 4096 joints"), std::string::npos)
      << skeleton.status().message();
}

TEST(MalformedInput, RandomMutationsOfValidFilesNeverCrash) {
  std::mt19937_64 rng(20240611);
  const std::string bvh = ReadText(FixturePath("custom_zxy.bvh"));
  const std::string asf_text = ReadText(FixturePath("tiny.asf"));
  const std::string amc = ReadText(FixturePath("tiny_01.amc"));
  Result<AsfSkeleton> asf = ParseAsf(asf_text, "tiny.asf");
  ASSERT_TRUE(asf.ok());
  int bvh_ok = 0;
  int amc_ok = 0;
  for (int round = 0; round < 3000; ++round) {
    Result<Take> bvh_take = ParseBvh(Mutate(bvh, &rng), "m.bvh");
    ExpectCleanResult(bvh_take, "m.bvh");
    bvh_ok += bvh_take.ok();
    Result<Take> amc_take = ParseAmc(*asf, Mutate(amc, &rng), "m.amc", 120);
    ExpectCleanResult(amc_take, "m.amc");
    amc_ok += amc_take.ok();
    Result<AsfSkeleton> mutated_asf = ParseAsf(Mutate(asf_text, &rng), "m.asf");
    if (mutated_asf.ok()) {
      // A mutated skeleton must still drive the AMC parser safely.
      ExpectCleanResult(ParseAmc(*mutated_asf, amc, "m2.amc", 120), "m2.amc");
      ASSERT_TRUE(AsfToSkeleton(*mutated_asf).Validate().ok());
    } else {
      ASSERT_TRUE(mutated_asf.status().IsInvalidArgument());
      ASSERT_EQ(mutated_asf.status().message().rfind("m.asf:", 0), 0u);
    }
    if (HasFatalFailure()) return;
  }
  // Some mutations are harmless (a changed digit); most are not. Both paths were exercised.
  EXPECT_GT(bvh_ok, 0);
  EXPECT_LT(bvh_ok, 3000);
  EXPECT_GT(amc_ok, 0);
  EXPECT_LT(amc_ok, 3000);
}

TEST(MalformedInput, RandomBytesAreRejectedCleanly) {
  std::mt19937_64 rng(7);
  Result<AsfSkeleton> asf = ParseAsf(ReadText(FixturePath("tiny.asf")), "tiny.asf");
  ASSERT_TRUE(asf.ok());
  for (int round = 0; round < 1000; ++round) {
    std::string bytes((rng)() % 400, '\0');
    for (char& byte : bytes) byte = static_cast<char>(rng() & 0xff);
    // Random prefixes of valid headers reach deeper parser states.
    if (round % 3 == 1) bytes = "HIERARCHY\nROOT r\n{\n" + bytes;
    if (round % 3 == 2) bytes = "1\nroot " + bytes;
    ExpectCleanResult(ParseBvh(bytes, "r.bvh"), "r.bvh");
    ExpectCleanResult(ParseAmc(*asf, bytes, "r.amc", 120), "r.amc");
    Result<AsfSkeleton> random_asf = ParseAsf(bytes, "r.asf");
    if (!random_asf.ok()) {
      ASSERT_TRUE(random_asf.status().IsInvalidArgument());
    }
    if (HasFatalFailure()) return;
  }
}

}  // namespace
}  // namespace motif
