// A small RFC 4180 reader for tests of the CSV files the tool writes (instances.csv): fields
// separated by commas, a quoted field may hold commas, doubled quotes and line breaks; records
// end in LF or CRLF. Written independently of the writer, so a test compares the file as a
// reader sees it. Header-only.
#pragma once

#include <string>
#include <vector>

namespace motif::testing {

// The records of `text`, each a list of fields. A malformed quote gives an empty result.
inline std::vector<std::vector<std::string>> ParseCsvRows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false;
  bool field_started = false;
  for (size_t at = 0; at < text.size(); ++at) {
    const char c = text[at];
    if (quoted) {
      if (c != '"') {
        field += c;
      } else if (at + 1 < text.size() && text[at + 1] == '"') {
        field += '"';
        ++at;
      } else {
        quoted = false;
      }
    } else if (c == '"') {
      if (!field.empty()) return {};  // a quote inside an unquoted field
      quoted = field_started = true;
    } else if (c == ',') {
      row.push_back(field);
      field.clear();
      field_started = true;
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && at + 1 < text.size() && text[at + 1] == '\n') ++at;
      row.push_back(field);
      rows.push_back(row);
      row.clear();
      field.clear();
      field_started = false;
    } else {
      field += c;
      field_started = true;
    }
  }
  if (quoted) return {};
  if (field_started || !row.empty()) {
    row.push_back(field);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace motif::testing
