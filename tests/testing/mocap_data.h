// Where the real CMU takes are (../shared/data/mocap beside the repository, or $MOTIF_MOCAP_DIR),
// and a macro that skips a test with a clear message when they are absent.
#pragma once

#include <string>

#include <gtest/gtest.h>

namespace motif::testing {

// The mocap folder; empty if it does not exist.
std::string MocapDir();

// The studio rig's takes (../shared/data/bandai2 beside the repository, or $MOTIF_BANDAI2_DIR):
// the folder holding bvh/; empty if it does not exist.
std::string StudioRigDir();

// The exercise routines (../shared/data/mocap6 beside the repository, or $MOTIF_MOCAP6_DIR): the
// folder holding 13.asf and the 13_29 .. 13_31 .amc takes; empty if it does not exist.
std::string ExerciseRoutinesDir();

}  // namespace motif::testing

// Skips the test with "WHAT not found (WHERE): skipping this test" when `dir` is empty.
#define MOTIF_SKIP_WITHOUT_DATA(dir, what_and_where)             \
  do {                                                           \
    if ((dir).empty()) {                                         \
      GTEST_SKIP() << what_and_where << ": skipping this test"; \
    }                                                            \
  } while (0)

#define MOTIF_REQUIRE_MOCAP_DATA()                                     \
  MOTIF_SKIP_WITHOUT_DATA(::motif::testing::MocapDir(),                \
                          "real CMU takes not found (../shared/data/mocap or $MOTIF_MOCAP_DIR)")

#define MOTIF_REQUIRE_STUDIO_RIG_DATA()                           \
  MOTIF_SKIP_WITHOUT_DATA(::motif::testing::StudioRigDir(),       \
                          "studio rig takes not found (../shared/data/bandai2 or " \
                          "$MOTIF_BANDAI2_DIR)")

#define MOTIF_REQUIRE_EXERCISE_ROUTINES()                                \
  MOTIF_SKIP_WITHOUT_DATA(::motif::testing::ExerciseRoutinesDir(),       \
                          "exercise routines not found (../shared/data/mocap6 or " \
                          "$MOTIF_MOCAP6_DIR)")
