#include "engine/cli/numeric_options.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <typeinfo>

namespace motif::cli {
namespace {

namespace po = boost::program_options;

// The highest frame rate accepted: capture systems record at up to a few thousand frames a
// second; 5e7 made the resampler allocate until the process was killed.
constexpr double kMaxFps = 10000.0;
// synth --frames: as the option table's --synth-frames (engine/pipeline/option_table.cc).
constexpr uint64_t kMaxSynthFrames = 100000000;

bool IsUnsigned(const std::type_info& type) {
  return type == typeid(uint32_t) || type == typeid(uint64_t) || type == typeid(size_t) ||
         type == typeid(uint16_t);
}

double AsDouble(const boost::any& value) {
  if (value.type() == typeid(double)) return boost::any_cast<double>(value);
  return boost::any_cast<float>(value);
}

Status Bad(const std::string& flag, const std::string& given, const std::string& rule) {
  return Status::InvalidArgument("--" + flag + " must be " + rule + ", not '" + given + "'");
}

Status CheckOne(const std::string& flag, const std::string& given, const boost::any& value) {
  const std::type_info& type = value.type();
  if (IsUnsigned(type) && given.find('-') != std::string::npos) {
    return Bad(flag, given, "a whole number >= 0");
  }
  // synth: the largest archive the project measures; more would write until the disk is full.
  if (flag == "frames" && type == typeid(uint64_t) &&
      boost::any_cast<uint64_t>(value) > kMaxSynthFrames) {
    return Bad(flag, given, "at most 100000000 (10^8 frames, about 7 GB)");
  }
  if (type != typeid(double) && type != typeid(float)) return Status::Ok();
  const double number = AsDouble(value);
  if (!std::isfinite(number)) return Bad(flag, given, "a finite number");
  const bool is_rate = flag == "fps" || flag == "bvh-fps" || flag == "amc-fps";
  if (is_rate && number != 0 && (number < 1 || number > kMaxFps)) {
    return Bad(flag, given, "between 1 and 10000 frames a second");
  }
  if (flag == "min-age" && number < 0) return Bad(flag, given, ">= 0 seconds");
  return Status::Ok();
}

}  // namespace

Status CheckNumericOptions(const po::parsed_options& parsed, const po::variables_map& vm) {
  for (const po::option& option : parsed.options) {
    if (option.position_key != -1 || option.value.empty() || !vm.count(option.string_key)) {
      continue;  // positional, a switch without a value, or not stored
    }
    const boost::any& value = vm[option.string_key].value();
    for (const std::string& given : option.value) {
      Status status = CheckOne(option.string_key, given, value);
      if (!status.ok()) return status;
    }
  }
  return Status::Ok();
}

}  // namespace motif::cli
