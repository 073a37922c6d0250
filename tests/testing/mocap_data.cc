#include "tests/testing/mocap_data.h"

#include <cstdlib>
#include <filesystem>

namespace motif::testing {

std::string MocapDir() {
  const char* from_env = std::getenv("MOTIF_MOCAP_DIR");
  std::string dir = from_env && *from_env ? from_env : MOTIF_MOCAP_DIR;
  std::error_code error;
  if (!std::filesystem::is_directory(dir + "/bvh", error)) return "";
  return std::filesystem::weakly_canonical(dir, error).string();
}

namespace {

// Folder `name` beside the CMU takes' folder, or $`variable`, when it holds `marker`; else "".
std::string DataBesideMocap(const char* variable, const char* name, const char* marker) {
  const char* from_env = std::getenv(variable);
  const std::string dir = from_env && *from_env
                              ? std::string(from_env)
                              : (std::filesystem::path(MOTIF_MOCAP_DIR) / ".." / name).string();
  std::error_code error;
  if (!std::filesystem::exists(dir + "/" + marker, error)) return "";
  return std::filesystem::weakly_canonical(dir, error).string();
}

}  // namespace

std::string StudioRigDir() { return DataBesideMocap("MOTIF_BANDAI2_DIR", "bandai2", "bvh"); }

std::string ExerciseRoutinesDir() {
  return DataBesideMocap("MOTIF_MOCAP6_DIR", "mocap6", "13.asf");
}

}  // namespace motif::testing
