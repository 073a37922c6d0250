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

#define MOTIF_REQUIRE_MOCAP_DATA()                                                          \
  do {                                                                                      \
    if (::motif::testing::MocapDir().empty()) {                                             \
      GTEST_SKIP() << "real CMU takes not found (../shared/data/mocap or $MOTIF_MOCAP_DIR)" \
                      ": skipping this test";                                               \
    }                                                                                       \
  } while (0)

#define MOTIF_REQUIRE_STUDIO_RIG_DATA()                                                 \
  do {                                                                                  \
    if (::motif::testing::StudioRigDir().empty()) {                                     \
      GTEST_SKIP() << "studio rig takes not found (../shared/data/bandai2 or "          \
                      "$MOTIF_BANDAI2_DIR): skipping this test";                        \
    }                                                                                   \
  } while (0)

#define MOTIF_REQUIRE_EXERCISE_ROUTINES()                                               \
  do {                                                                                  \
    if (::motif::testing::ExerciseRoutinesDir().empty()) {                              \
      GTEST_SKIP() << "exercise routines not found (../shared/data/mocap6 or "          \
                      "$MOTIF_MOCAP6_DIR): skipping this test";                         \
    }                                                                                   \
  } while (0)
