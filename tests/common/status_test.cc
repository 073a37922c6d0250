#include "common/status.h"

#include <cerrno>

#include <gtest/gtest.h>

namespace motif {
namespace {

TEST(Status, CodesArePinned) {
  EXPECT_EQ(static_cast<int>(Status::Code::kOk), 0);
  EXPECT_EQ(static_cast<int>(Status::Code::kNotFound), 1);
  EXPECT_EQ(static_cast<int>(Status::Code::kCorruption), 2);
  EXPECT_EQ(static_cast<int>(Status::Code::kInvalidArgument), 3);
  EXPECT_EQ(static_cast<int>(Status::Code::kIOError), 4);
  EXPECT_EQ(static_cast<int>(Status::Code::kNotSupported), 5);
  EXPECT_EQ(static_cast<int>(Status::Code::kResourceExhausted), 6);
  EXPECT_EQ(static_cast<int>(Status::Code::kBusy), 7);
}

TEST(Status, ToStringNamesCodeAndMessage) {
  EXPECT_EQ(Status::Ok().ToString(), "OK");
  EXPECT_EQ(Status::Corruption("a.mfs: block 3: checksum mismatch").ToString(),
            "Corruption: a.mfs: block 3: checksum mismatch");
  EXPECT_EQ(Status::InvalidArgument("x").WithContext("b.bvh").message(), "b.bvh: x");
}

TEST(Status, FullDiskIsResourceExhausted) {
  EXPECT_EQ(Status::FromErrno("w", ENOSPC).code(), Status::Code::kResourceExhausted);
  EXPECT_EQ(Status::FromErrno("w", EIO).code(), Status::Code::kIOError);
  EXPECT_EQ(Status::FromErrno("w", ENOENT).code(), Status::Code::kNotFound);
}

Result<int> Half(int value) {
  if (value % 2 != 0) return Status::InvalidArgument(std::to_string(value) + " is odd");
  return value / 2;
}

Status Quarter(int value, int* out) {
  MOTIF_ASSIGN_OR_RETURN(int half, Half(value));
  MOTIF_ASSIGN_OR_RETURN(*out, Half(half));
  return Status::Ok();
}

TEST(Result, PropagatesTheFirstError) {
  int out = 0;
  EXPECT_TRUE(Quarter(8, &out).ok());
  EXPECT_EQ(out, 2);
  Status status = Quarter(6, &out);
  EXPECT_TRUE(status.IsInvalidArgument());
  EXPECT_EQ(status.message(), "3 is odd");
}

// Reading the value of an error is a bug of the caller: it must stop the program with the
// status, not read an empty optional.
TEST(ResultDeathTest, ValueOfAnErrorAbortsNamingTheStatus) {
  Result<int> failed = Half(3);
  ASSERT_FALSE(failed.ok());
  EXPECT_DEATH((void)failed.value(), "Result::value\\(\\) on an error: InvalidArgument: 3 is odd");
  EXPECT_DEATH((void)*failed, "3 is odd");
  Result<std::string> missing = Status::NotFound("no such take");
  EXPECT_DEATH((void)missing->size(), "NotFound: no such take");
}

}  // namespace
}  // namespace motif
