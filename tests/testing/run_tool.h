// Running the built `motifmine` binary (or any shell command) from a test, as a user would, and
// collecting its exit code and output.
#pragma once

#include <string>

namespace motif::testing {

struct RunResult {
  int exit_code = -1;  // -1 if the command could not run or did not exit normally
  std::string output;  // what the command printed (its stderr too when redirected)
};

// Runs `command` with /bin/sh and waits for it.
RunResult RunShell(const std::string& command);

#ifdef MOTIF_TOOL
// `motifmine ARGUMENTS`, stdout and stderr together. MOTIF_TOOL is the binary's path, defined per
// test target (tests/engine/cli/CMakeLists.txt).
inline RunResult RunTool(const std::string& arguments) {
  std::string command = MOTIF_TOOL;
  command.append(" ").append(arguments).append(" 2>&1");
  return RunShell(command);
}
#endif

}  // namespace motif::testing
