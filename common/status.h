// Status and Result<T>: how every function that touches disk, decodes bytes or parses an import
// reports failure. A Status is a code plus a message that
// names the file and the place (line, block, byte offset). Codes are pinned: they appear in logs
// and in the command-line tool's exit codes (docs/guide.md), so their values never change.
// Broken invariants (our own bugs) abort through MOTIF_CHECK instead.
// Both are [[nodiscard]]: a returned Status or Result must be checked, or ignored explicitly
// with `(void)` and a comment saying why. Result's value(), * and -> on an error abort with the
// status on stderr (reading a value that is not there is a bug of the caller).
// Thread-safety: values; safe to copy between threads.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace motif {

class [[nodiscard]] Status {
 public:
  enum class Code : int {
    kOk = 0,
    kNotFound = 1,
    kCorruption = 2,
    kInvalidArgument = 3,
    kIOError = 4,
    kNotSupported = 5,
    kResourceExhausted = 6,
    kBusy = 7,  // another process holds the lock of what this one would write
  };

  Status() = default;
  static Status Ok() { return Status(); }
  static Status NotFound(std::string msg) { return Status(Code::kNotFound, std::move(msg)); }
  static Status Corruption(std::string msg) { return Status(Code::kCorruption, std::move(msg)); }
  static Status InvalidArgument(std::string msg) {
    return Status(Code::kInvalidArgument, std::move(msg));
  }
  static Status IOError(std::string msg) { return Status(Code::kIOError, std::move(msg)); }
  static Status NotSupported(std::string msg) {
    return Status(Code::kNotSupported, std::move(msg));
  }
  static Status ResourceExhausted(std::string msg) {
    return Status(Code::kResourceExhausted, std::move(msg));
  }
  static Status Busy(std::string msg) { return Status(Code::kBusy, std::move(msg)); }
  // An impossible value of the option `name`, as the option table names it ("kmax"): the
  // message is "kmax <problem>", and option() is "kmax", so that the tool can say "--kmax" and
  // Python the keyword (engine/pipeline/option_table.h).
  static Status InvalidOption(const std::string& name, const std::string& problem) {
    return Status(Code::kInvalidArgument, name + " " + problem).WithOption(name);
  }
  // The same status, about the option `name`, which its message names as a word ("... (asf)"):
  // the tool prints that word as its flag ("(--asf)").
  Status WithOption(const std::string& name) const {
    Status status = *this;
    status.option_ = name;
    return status;
  }
  // A status received as its code and message (from another process of a distributed run).
  static Status FromCode(Code code, std::string msg) { return Status(code, std::move(msg)); }
  // An IOError built from errno: "<context>: <strerror(errno)>". ENOSPC and EDQUOT become
  // kResourceExhausted so callers can tell a full disk from a broken one.
  static Status FromErrno(const std::string& context, int errno_value);

  bool ok() const { return code_ == Code::kOk; }
  Code code() const { return code_; }
  const std::string& message() const { return message_; }
  // The option an InvalidOption status is about; empty otherwise.
  const std::string& option() const { return option_; }
  // "Corruption: <message>", or "OK".
  std::string ToString() const;
  // The same status with "<prefix>: " put before the message (no-op on OK).
  Status WithContext(const std::string& prefix) const;

  bool IsNotFound() const { return code_ == Code::kNotFound; }
  bool IsCorruption() const { return code_ == Code::kCorruption; }
  bool IsInvalidArgument() const { return code_ == Code::kInvalidArgument; }
  bool IsIOError() const { return code_ == Code::kIOError; }
  bool IsBusy() const { return code_ == Code::kBusy; }
  bool IsNotSupported() const { return code_ == Code::kNotSupported; }

 private:
  Status(Code code, std::string msg) : code_(code), message_(std::move(msg)) {}
  Code code_ = Code::kOk;
  std::string message_;
  std::string option_;
};

const char* StatusCodeName(Status::Code code);

namespace internal {
// Prints "Result::value() on an error: <status>" to stderr and aborts.
[[noreturn]] void DieOnResultError(const Status& status);
}  // namespace internal

// A value or a non-OK Status.
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}         // NOLINT: implicit by design
  Result(Status status) : status_(std::move(status)) {  // NOLINT: implicit by design
    if (status_.ok()) {
      std::fprintf(stderr, "Result constructed from an OK status without a value\n");
      std::abort();
    }
  }
  bool ok() const { return status_.ok(); }
  const Status& status() const { return status_; }
  // On an error these abort with the status (internal::DieOnResultError).
  T& value() & {
    CheckHasValue();
    return *value_;
  }
  const T& value() const& {
    CheckHasValue();
    return *value_;
  }
  T&& value() && {
    CheckHasValue();
    return std::move(*value_);
  }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

 private:
  void CheckHasValue() const {
    if (!value_.has_value()) [[unlikely]]
      internal::DieOnResultError(status_);
  }
  Status status_;
  std::optional<T> value_;
};

}  // namespace motif

#define MOTIF_CONCAT_INNER(a, b) a##b
#define MOTIF_CONCAT(a, b) MOTIF_CONCAT_INNER(a, b)

#define MOTIF_RETURN_IF_ERROR(expr)                \
  do {                                             \
    ::motif::Status motif_status_ = (expr);        \
    if (!motif_status_.ok()) return motif_status_; \
  } while (0)

#define MOTIF_ASSIGN_OR_RETURN_IMPL(tmp, lhs, expr) \
  auto tmp = (expr);                                \
  if (!tmp.ok()) return tmp.status();               \
  lhs = std::move(tmp).value()

#define MOTIF_ASSIGN_OR_RETURN(lhs, expr) \
  MOTIF_ASSIGN_OR_RETURN_IMPL(MOTIF_CONCAT(motif_result_, __LINE__), lhs, expr)

// Aborts with the condition, file and line when an internal invariant is broken.
#define MOTIF_CHECK(cond)                                                           \
  do {                                                                              \
    if (!(cond)) {                                                                  \
      std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
      std::abort();                                                                 \
    }                                                                               \
  } while (0)
