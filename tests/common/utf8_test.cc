#include "common/utf8.h"

#include <string>

#include <gtest/gtest.h>

namespace motif {
namespace {

TEST(IsValidUtf8, AcceptsWellFormedTextAndRefusesEveryKindOfMalformedByte) {
  EXPECT_TRUE(IsValidUtf8(""));
  EXPECT_TRUE(IsValidUtf8("05_01-walk.bvh"));
  EXPECT_TRUE(IsValidUtf8("t\xc3\xa9l\xc3\xa9"));         // é, 2 bytes
  EXPECT_TRUE(IsValidUtf8("\xe2\x82\xac"));               // €, 3 bytes
  EXPECT_TRUE(IsValidUtf8("\xf0\x9f\x92\x83"));           // U+1F483, 4 bytes
  EXPECT_TRUE(IsValidUtf8("\xf4\x8f\xbf\xbf"));           // U+10FFFF, the last
  EXPECT_FALSE(IsValidUtf8("take\xff.bvh"));              // never in UTF-8
  EXPECT_FALSE(IsValidUtf8("\x80"));                      // a continuation byte first
  EXPECT_FALSE(IsValidUtf8("\xc3"));                      // cut short
  EXPECT_FALSE(IsValidUtf8("\xe2\x82"));                  // cut short
  EXPECT_FALSE(IsValidUtf8("\xc3\x28"));                  // not a continuation byte
  EXPECT_FALSE(IsValidUtf8("\xc0\xaf"));                  // overlong '/'
  EXPECT_FALSE(IsValidUtf8("\xe0\x80\xaf"));              // overlong '/'
  EXPECT_FALSE(IsValidUtf8("\xed\xa0\x80"));              // a surrogate, U+D800
  EXPECT_FALSE(IsValidUtf8("\xf4\x90\x80\x80"));          // above U+10FFFF
  EXPECT_FALSE(IsValidUtf8(std::string("ok\0\xfe", 4)));  // NUL is fine, 0xfe is not
  EXPECT_TRUE(IsValidUtf8(std::string("a\0b", 3)));
}

}  // namespace
}  // namespace motif
