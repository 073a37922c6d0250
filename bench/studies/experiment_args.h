// key=value command-line arguments of the LSH study tools (lsh_experiment, refine_experiment).
#pragma once

#include <cstdlib>
#include <map>
#include <string>

namespace motif::testing {

class ExperimentArgs {
 public:
  ExperimentArgs(int argc, char** argv) {
    for (int idx = 1; idx < argc; ++idx) {
      const std::string arg = argv[idx];
      const auto eq = arg.find('=');
      values_[arg.substr(0, eq)] = eq == std::string::npos ? "1" : arg.substr(eq + 1);
    }
  }
  bool has(const std::string& key) const { return values_.count(key) > 0; }
  double number(const std::string& key, double fallback) const {
    return has(key) ? std::atof(values_.at(key).c_str()) : fallback;
  }
  std::string text(const std::string& key, const std::string& fallback = "") const {
    return has(key) ? values_.at(key) : fallback;
  }
  std::map<std::string, std::string>& values() { return values_; }

 private:
  std::map<std::string, std::string> values_;
};

}  // namespace motif::testing
