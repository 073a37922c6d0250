#include "common/status.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace motif {

const char* StatusCodeName(Status::Code code) {
  switch (code) {
    case Status::Code::kOk:
      return "OK";
    case Status::Code::kNotFound:
      return "NotFound";
    case Status::Code::kCorruption:
      return "Corruption";
    case Status::Code::kInvalidArgument:
      return "InvalidArgument";
    case Status::Code::kIOError:
      return "IOError";
    case Status::Code::kNotSupported:
      return "NotSupported";
    case Status::Code::kResourceExhausted:
      return "ResourceExhausted";
    case Status::Code::kBusy:
      return "Busy";
  }
  return "Unknown";
}

Status Status::FromErrno(const std::string& context, int errno_value) {
  std::string msg = context + ": " + std::strerror(errno_value);
  if (errno_value == ENOSPC || errno_value == EDQUOT) return ResourceExhausted(std::move(msg));
  if (errno_value == ENOENT) return NotFound(std::move(msg));
  return IOError(std::move(msg));
}

std::string Status::ToString() const {
  if (ok()) return "OK";
  return std::string(StatusCodeName(code_)) + ": " + message_;
}

namespace internal {
void DieOnResultError(const Status& status) {
  std::fprintf(stderr, "Result::value() on an error: %s\n", status.ToString().c_str());
  std::abort();
}
}  // namespace internal

Status Status::WithContext(const std::string& prefix) const {
  if (ok()) return *this;
  Status status(code_, prefix + ": " + message_);
  status.option_ = option_;
  return status;
}

}  // namespace motif
