// The main() of every test program: GoogleTest's own, plus one rule. ctest counts a test as
// skipped when its output holds "[  SKIPPED ]", whatever its exit code, and GoogleTest prints that
// for every test of a suite whose SetUpTestSuite failed: a broken fixture would pass CI as a
// skip. So a failure outside any test (a suite's or the environment's set-up) ends the program
// at once, with exit code 1, before any test is reported skipped.
#include <atomic>
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

namespace {

// Tracks whether a test is running itself: asking GoogleTest (current_test_info) from inside
// OnTestPartResult would wait on the lock GoogleTest holds while calling it.
class FailOutsideTests : public ::testing::EmptyTestEventListener {
  void OnTestStart(const ::testing::TestInfo&) override { in_test_ = true; }
  void OnTestEnd(const ::testing::TestInfo&) override { in_test_ = false; }
  void OnTestPartResult(const ::testing::TestPartResult& result) override {
    if (!result.failed() || in_test_) return;
    std::printf("motif-test: a failure outside any test (a suite's set-up); stopping\n");
    std::fflush(nullptr);
    std::_Exit(1);
  }
  std::atomic<bool> in_test_{false};
};

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  // Appended after GoogleTest's printer, which has printed the failure by then.
  ::testing::UnitTest::GetInstance()->listeners().Append(new FailOutsideTests);
  return RUN_ALL_TESTS();
}
