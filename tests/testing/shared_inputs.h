// SharedInputs: test inputs made once per build and reused by every test process. ctest runs
// each test in a process of its own, so a suite's SetUpTestSuite would otherwise make the same
// takes again for every test of the suite (9 times for the reindex command's suite).
//
// The inputs live in MOTIF_TEST_CACHE_DIR (the build tree's test-inputs/), in a folder named by
// the caller's key and by the size and modification time of the executables that make them
// (ExecutableStamp), so that a rebuilt tool or test makes them again. A folder is made under a
// temporary name and renamed into place whole: tests running side by side either find it
// finished or make their own copy, and the first rename wins.
#pragma once

#include <functional>
#include <string>

namespace motif::testing {

// "<size>-<mtime in ns>" of the file at `path`, or "missing".
std::string ExecutableStamp(const std::string& path);

// The folder of `key`, made by `make(folder)` when no finished one exists. `make` returns false
// (after a gtest failure) when it could not make the inputs; the folder is then dropped and ""
// returned.
std::string SharedInputs(const std::string& key,
                         const std::function<bool(const std::string&)>& make);

}  // namespace motif::testing
