#include "formats/import/take_descriptions.h"

#include <filesystem>
#include <sstream>
#include <vector>

#include <boost/algorithm/string/split.hpp>

#include "common/file_util.h"
#include "common/utf8.h"

namespace motif {

Result<std::unordered_map<std::string, std::string>> ReadTakeDescriptions(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(std::string text, ReadFileToString(path, uint64_t{64} << 20));
  if (!IsValidUtf8(text)) return Status::InvalidArgument(path + ": not UTF-8 text");
  std::istringstream lines(text);
  std::string line;
  size_t line_number = 0;
  int file_column = -1, description_column = -1;
  std::unordered_map<std::string, std::string> descriptions;
  while (std::getline(lines, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    boost::algorithm::split(fields, line, [](char c) { return c == '\t'; });
    const std::string where = path + ":" + std::to_string(line_number);
    if (file_column < 0) {  // the header
      for (size_t idx = 0; idx < fields.size(); ++idx) {
        if (fields[idx] == "file") file_column = static_cast<int>(idx);
        if (fields[idx] == "description") description_column = static_cast<int>(idx);
      }
      if (file_column < 0 || description_column < 0) {
        return Status::InvalidArgument(where +
                                       ": the header needs a 'file' and a 'description' column "
                                       "(tab-separated)");
      }
      continue;
    }
    if (static_cast<int>(fields.size()) <= std::max(file_column, description_column)) {
      return Status::InvalidArgument(where + ": " + std::to_string(fields.size()) +
                                     " columns, the header names more");
    }
    const std::string name = std::filesystem::path(fields[file_column]).stem().string();
    if (name.empty()) return Status::InvalidArgument(where + ": an empty file name");
    const std::string& description = fields[description_column];
    auto [it, inserted] = descriptions.emplace(name, description);
    if (!inserted && it->second != description) {
      return Status::InvalidArgument(where + ": take '" + name +
                                     "' was given another description on an earlier line");
    }
  }
  if (file_column < 0) return Status::InvalidArgument(path + ": no header line");
  return descriptions;
}

}  // namespace motif
