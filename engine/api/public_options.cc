// The option table of the public API (include/motifmine/options.h), over the engine's
// (engine/pipeline/option_table.h).
#include "engine/api/public_status.h"
#include "engine/pipeline/option_table.h"
#include "motifmine/options.h"

namespace motifmine {

std::vector<OptionInfo> MineOptionTable() {
  std::vector<OptionInfo> table;
  for (const motif::OptionSpec& spec : motif::MineOptionSpecs()) table.push_back(spec.info);
  return table;
}

Status SetMineOption(MineOptions* options, const std::string& name, const std::string& value) {
  if (options == nullptr) return {Status::Code::kInvalidArgument, "no MineOptions to set"};
  return motif::ToPublicStatus(motif::SetOptionFromText(options, name, value));
}

std::string GetMineOption(const MineOptions& options, const std::string& name) {
  return motif::OptionAsText(options, name);
}

}  // namespace motifmine
