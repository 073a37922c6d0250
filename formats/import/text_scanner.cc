#include "formats/import/text_scanner.h"

#include <charconv>
#include <cmath>
#include <cstring>

namespace motif::import_internal {

bool ParseDouble(std::string_view token, double* value) {
  const char* begin = token.data();
  const char* end = begin + token.size();
  // from_chars, unlike strtod, rejects a leading '+'; some exporters write one.
  if (begin != end && *begin == '+') ++begin;
  if (begin == end) return false;
  // Reject "nan"/"inf" spellings before from_chars accepts them; also rejects "+-1".
  const char first = (*begin == '-' && begin + 1 != end) ? begin[1] : *begin;
  if (!((first >= '0' && first <= '9') || first == '.')) return false;
  const auto [ptr, error] = std::from_chars(begin, end, *value);
  return error == std::errc() && ptr == end && std::isfinite(*value);
}

bool ParseInt64(std::string_view token, int64_t* value) {
  const char* begin = token.data();
  const char* end = begin + token.size();
  if (begin != end && *begin == '+') ++begin;
  if (begin == end) return false;
  const auto [ptr, error] = std::from_chars(begin, end, *value);
  return error == std::errc() && ptr == end;
}

bool EqualsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t idx = 0; idx < a.size(); ++idx) {
    char ca = a[idx];
    char cb = b[idx];
    if (ca >= 'A' && ca <= 'Z') ca = static_cast<char>(ca - 'A' + 'a');
    if (cb >= 'A' && cb <= 'Z') cb = static_cast<char>(cb - 'A' + 'a');
    if (ca != cb) return false;
  }
  return true;
}

std::string Printable(std::string_view text) {
  constexpr size_t kMaxChars = 40;
  std::string out;
  for (size_t idx = 0; idx < text.size() && idx < kMaxChars; ++idx) {
    const unsigned char c = static_cast<unsigned char>(text[idx]);
    if (c >= 0x20 && c < 0x7f) {
      out.push_back(static_cast<char>(c));
    } else {
      static const char kHex[] = "0123456789abcdef";
      out += "\\x";
      out.push_back(kHex[c >> 4]);
      out.push_back(kHex[c & 15]);
    }
  }
  if (text.size() > kMaxChars) out += "...";
  return out;
}

std::string Quoted(std::string_view text) {
  // Appended piecewise: GCC 12 warns (-Wrestrict, a false positive) on "'" + std::string&&.
  std::string quoted(1, '\'');
  quoted += Printable(text);
  quoted.push_back('\'');
  return quoted;
}

bool NextWord(std::string_view* rest, std::string_view* word) {
  size_t pos = 0;
  while (pos < rest->size() && IsBlank((*rest)[pos])) ++pos;
  if (pos == rest->size()) {
    *rest = std::string_view();
    return false;
  }
  size_t end = pos;
  while (end < rest->size() && !IsBlank((*rest)[end])) ++end;
  *word = rest->substr(pos, end - pos);
  *rest = rest->substr(end);
  return true;
}

bool LineCursor::Next(std::string_view* line) {
  if (pos_ >= text_.size()) return false;
  const char* start = text_.data() + pos_;
  const void* newline = std::memchr(start, '\n', text_.size() - pos_);
  size_t length = newline ? static_cast<const char*>(newline) - start : text_.size() - pos_;
  pos_ += length + (newline ? 1 : 0);
  if (length > 0 && start[length - 1] == '\r') --length;
  *line = std::string_view(start, length);
  ++next_line_number_;
  return true;
}

void Tokenizer::SkipBlanks() {
  while (pos_ < text_.size() && IsBlank(text_[pos_])) {
    if (text_[pos_] == '\n') ++line_;
    ++pos_;
  }
}

bool Tokenizer::Next(Token* token) {
  SkipBlanks();
  if (pos_ >= text_.size()) return false;
  const size_t start = pos_;
  while (pos_ < text_.size() && !IsBlank(text_[pos_])) ++pos_;
  token->text = text_.substr(start, pos_ - start);
  token->line = line_;
  last_token_line_ = line_;
  return true;
}

bool Tokenizer::Peek(Token* token) {
  const size_t saved_pos = pos_;
  const int saved_line = line_;
  const int saved_last_token_line = last_token_line_;
  const bool found = Next(token);
  pos_ = saved_pos;
  line_ = saved_line;
  last_token_line_ = saved_last_token_line;
  return found;
}

}  // namespace motif::import_internal
