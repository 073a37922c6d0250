#include "engine/cli/clip_range_take.h"

#include <cstdio>
#include <string>
#include <vector>

namespace motif::cli {

void AddJointNamesOption(boost::program_options::options_description* options) {
  options->add_options()(
      "names", boost::program_options::value<std::string>()->default_value("source"),
      "joint names: source (those of the imported file, e.g. a BVH's LeftUpLeg) or canonical "
      "(the archive's, e.g. lfemur)");
}

bool CheckJointNamesOption(const std::string& command, const std::string& usage,
                           const boost::program_options::variables_map& vm) {
  const std::string names = vm["names"].as<std::string>();
  if (names == "source" || names == "canonical") return true;
  std::fprintf(stderr, "motifmine %s: --names must be source or canonical, not '%s'\nusage: %s\n",
               command.c_str(), names.c_str(), usage.c_str());
  return false;
}

void ApplyJointNamesOption(const boost::program_options::variables_map& vm, Take* take) {
  if (vm["names"].as<std::string>() != "source") return;
  if (take->source_joint_names.size() != take->skeleton.joint_count()) return;
  for (size_t joint_idx = 0; joint_idx < take->skeleton.joint_count(); ++joint_idx) {
    take->skeleton.mutable_joints()[joint_idx].name = take->source_joint_names[joint_idx];
  }
}

}  // namespace motif::cli
