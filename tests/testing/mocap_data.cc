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

}  // namespace motif::testing
