// Text scanning shared by the BVH, ASF and AMC parsers (private to formats/import): a line cursor
// that counts lines and strips CR, a whitespace tokenizer that remembers each token's line, and a
// strict number parser built on std::from_chars (a leading '+' is accepted; NaN, infinities and
// trailing characters are rejected). Error messages quote tokens through Printable(), so binary
// garbage in a file never reaches a log as raw bytes.
// Thread-safety: values; each parser owns its own scanners.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace motif::import_internal {

// The largest rotation a channel may hold, in degrees (the BVH and AMC parsers). A take's frames
// are stored as float quaternions of the angle: at 10^6 degrees a float still places it within
// 0.06 degrees; far beyond, as at 1e308, the angle is noise and the pose cannot be motion, so
// the take is bad.
inline constexpr double kMaxRotationDegrees = 1e6;

inline bool IsBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

// Parses the whole of `token` as a finite double. False for an empty token, trailing characters,
// NaN, infinities and out-of-range values.
bool ParseDouble(std::string_view token, double* value);

// Parses the whole of `token` as a decimal integer (optional sign).
bool ParseInt64(std::string_view token, int64_t* value);

// Case-insensitive ASCII comparison.
bool EqualsIgnoreCase(std::string_view a, std::string_view b);

// `text` made safe to quote in a message: at most 40 characters, non-printable bytes as \xNN.
std::string Printable(std::string_view text);

// Printable(text) in single quotes.
std::string Quoted(std::string_view text);

// Splits off the next whitespace-separated token of `*rest` (consuming it). False when none.
bool NextWord(std::string_view* rest, std::string_view* word);

// Lines of a text, LF or CRLF terminated (a final line without a newline counts).
class LineCursor {
 public:
  explicit LineCursor(std::string_view text, int first_line_number = 1)
      : text_(text), next_line_number_(first_line_number) {}

  // The next line without its terminator; false at the end of the text.
  bool Next(std::string_view* line);
  // Number of the line last returned by Next() (1-based).
  int line_number() const { return next_line_number_ - 1; }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  int next_line_number_;
};

// Whitespace-separated tokens with the line each starts on.
struct Token {
  std::string_view text;
  int line = 0;
};

class Tokenizer {
 public:
  explicit Tokenizer(std::string_view text) : text_(text) {}

  // The next token; false at the end of the text.
  bool Next(Token* token);
  // The next token without consuming it.
  bool Peek(Token* token);
  // The text after the last token returned (for switching to line-based reading), and the line
  // number that text starts on.
  std::string_view Rest() const { return text_.substr(pos_); }
  int line() const { return line_; }
  // Line of the last token returned by Next() (1 before any): where "file ends" errors point.
  int last_token_line() const { return last_token_line_; }

 private:
  void SkipBlanks();

  std::string_view text_;
  size_t pos_ = 0;
  int line_ = 1;
  int last_token_line_ = 1;
};

}  // namespace motif::import_internal
