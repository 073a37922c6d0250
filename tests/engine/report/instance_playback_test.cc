#include "engine/report/instance_playback.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace motif {
namespace {

TEST(InstancePlayback, Base64OfTheStandardVectors) {  // RFC 4648, section 10
  // On the heap, exactly as long as the text: a read past its end shows under ASan / valgrind.
  auto encode = [](const std::string& text) {
    const std::vector<uint8_t> bytes(text.begin(), text.end());
    return Base64(bytes.data(), bytes.size());
  };
  EXPECT_EQ(encode(""), "");
  EXPECT_EQ(encode("f"), "Zg==");
  EXPECT_EQ(encode("fo"), "Zm8=");
  EXPECT_EQ(encode("foo"), "Zm9v");
  EXPECT_EQ(encode("foob"), "Zm9vYg==");
  EXPECT_EQ(encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
  const uint8_t high[] = {0xff, 0xfe, 0x80};
  EXPECT_EQ(Base64(high, 3), "//6A");
}

TEST(InstancePlayback, JointSidesFromCmuAndBvhNames) {
  for (const char* left : {"lfemur", "ltibia", "lhumerus", "lhipjoint", "LeftUpLeg", "LeftArm"}) {
    EXPECT_EQ(JointSide(left), 1) << left;
  }
  for (const char* right : {"rfemur", "rradius", "rclavicle", "RightFoot", "RightHand"}) {
    EXPECT_EQ(JointSide(right), 2) << right;
  }
  for (const char* centre : {"root", "lowerback", "lowerneck", "upperback", "thorax", "head",
                             "Hips", "Spine", "Neck", "l", "r"}) {
    EXPECT_EQ(JointSide(centre), 0) << centre;
  }
}

}  // namespace
}  // namespace motif
