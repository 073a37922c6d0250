#include "engine/api/public_status.h"

namespace motifmine {

// The public codes are the engine's plus 10, the tool's exit codes (docs/guide.md).
inline constexpr int kExitCodeBase = 10;
static_assert(static_cast<int>(Status::Code::kNotFound) ==
              kExitCodeBase + static_cast<int>(motif::Status::Code::kNotFound));
static_assert(static_cast<int>(Status::Code::kBusy) ==
              kExitCodeBase + static_cast<int>(motif::Status::Code::kBusy));

std::string Status::ToString() const {
  if (ok()) return "OK";
  // The engine's names, so the library and the tool say the same.
  const auto engine_code =
      static_cast<motif::Status::Code>(static_cast<int>(code_) - kExitCodeBase);
  return std::string(motif::StatusCodeName(engine_code)) + ": " + message_;
}

}  // namespace motifmine

namespace motif {

motifmine::Status ToPublicStatus(const Status& status) {
  if (status.ok()) return {};
  return {static_cast<motifmine::Status::Code>(static_cast<int>(status.code()) +
                                               motifmine::kExitCodeBase),
          status.message()};
}

}  // namespace motif
