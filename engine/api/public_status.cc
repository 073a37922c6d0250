#include "engine/api/public_status.h"

namespace motifmine {

std::string Status::ToString() const {
  if (ok()) return "OK";
  // The engine's names, so the library and the tool say the same.
  const auto engine_code = [](Code code) {
    switch (code) {
      case Code::kOk:
        return motif::Status::Code::kOk;
      case Code::kNotFound:
        return motif::Status::Code::kNotFound;
      case Code::kCorruption:
        return motif::Status::Code::kCorruption;
      case Code::kInvalidArgument:
        return motif::Status::Code::kInvalidArgument;
      case Code::kIOError:
        return motif::Status::Code::kIOError;
      case Code::kNotSupported:
        return motif::Status::Code::kNotSupported;
      case Code::kResourceExhausted:
        return motif::Status::Code::kResourceExhausted;
      case Code::kBusy:
        return motif::Status::Code::kBusy;
    }
    return motif::Status::Code::kIOError;
  };
  return std::string(motif::StatusCodeName(engine_code(code_))) + ": " + message_;
}

}  // namespace motifmine

namespace motif {

motifmine::Status ToPublicStatus(const Status& status) {
  using Code = motifmine::Status::Code;
  switch (status.code()) {
    case Status::Code::kOk:
      return {};
    case Status::Code::kNotFound:
      return {Code::kNotFound, status.message()};
    case Status::Code::kCorruption:
      return {Code::kCorruption, status.message()};
    case Status::Code::kInvalidArgument:
      return {Code::kInvalidArgument, status.message()};
    case Status::Code::kIOError:
      return {Code::kIOError, status.message()};
    case Status::Code::kNotSupported:
      return {Code::kNotSupported, status.message()};
    case Status::Code::kResourceExhausted:
      return {Code::kResourceExhausted, status.message()};
    case Status::Code::kBusy:
      return {Code::kBusy, status.message()};
  }
  return {Code::kIOError, status.message()};
}

}  // namespace motif
