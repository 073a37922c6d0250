#include "engine/cli/take_labels.h"

#include <sstream>

#include "common/file_util.h"

namespace motif::cli {

Result<TakeLabels> ReadTakeLabels(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(std::string text, ReadFileToString(path));
  TakeLabels labels;
  std::istringstream lines(text);
  std::string line;
  int line_number = 0;
  while (std::getline(lines, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::string where = path + ":" + std::to_string(line_number) + ": ";
    const size_t tab = line.find('\t');
    const std::string clip = line.substr(0, tab);
    if (line_number == 1 && clip == "clip") continue;
    if (tab == std::string::npos) {
      return Status::InvalidArgument(where + "expected 'clip<TAB>label', found no tab");
    }
    const size_t end = line.find('\t', tab + 1);
    const std::string label = line.substr(tab + 1, end == std::string::npos ? end : end - tab - 1);
    if (clip.empty() || label.empty()) {
      return Status::InvalidArgument(where + "an empty clip name or label");
    }
    if (!labels.by_clip.emplace(clip, label).second) {
      return Status::InvalidArgument(where + "clip '" + clip + "' is labelled twice");
    }
  }
  return labels;
}

}  // namespace motif::cli
