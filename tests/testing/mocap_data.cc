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

std::string StudioRigDir() {
  const char* from_env = std::getenv("MOTIF_BANDAI2_DIR");
  const std::string dir = from_env && *from_env
                              ? std::string(from_env)
                              : (std::filesystem::path(MOTIF_MOCAP_DIR) / ".." / "bandai2").string();
  std::error_code error;
  if (!std::filesystem::is_directory(dir + "/bvh", error)) return "";
  return std::filesystem::weakly_canonical(dir, error).string();
}

std::string ExerciseRoutinesDir() {
  const char* from_env = std::getenv("MOTIF_MOCAP6_DIR");
  const std::string dir = from_env && *from_env
                              ? std::string(from_env)
                              : (std::filesystem::path(MOTIF_MOCAP_DIR) / ".." / "mocap6").string();
  std::error_code error;
  if (!std::filesystem::is_regular_file(dir + "/13.asf", error)) return "";
  return std::filesystem::weakly_canonical(dir, error).string();
}

}  // namespace motif::testing
