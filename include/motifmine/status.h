// motifmine::Status: the outcome of a library call, in the manner of LevelDB's. A call either
// succeeds (ok()) or fails with a code and a message that names the file, the option or the
// problem. Part of the public API (<motifmine/motifmine.h>); no third-party type.
#pragma once

#include <string>

#include "motifmine/export.h"

namespace motifmine {

class [[nodiscard]] MOTIFMINE_API Status {
 public:
  // The codes, each with the motifmine tool's exit code for it (docs/guide.md, "Exit codes").
  enum class Code {
    kOk = 0,
    kNotFound = 11,
    kCorruption = 12,
    kInvalidArgument = 13,
    kIOError = 14,
    kNotSupported = 15,
    kResourceExhausted = 16,
    kBusy = 17,
  };

  Status() = default;  // OK
  Status(Code code, std::string message) : code_(code), message_(std::move(message)) {}

  bool ok() const { return code_ == Code::kOk; }
  Code code() const { return code_; }
  const std::string& message() const { return message_; }
  // "OK", or the code's name and the message: "InvalidArgument: --kmax must be > 0".
  std::string ToString() const;

 private:
  Code code_ = Code::kOk;
  std::string message_;
};

}  // namespace motifmine
