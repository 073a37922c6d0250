#include "engine/evaluation/motif_truth.h"

#include <charconv>
#include <sstream>

#include <boost/algorithm/string/split.hpp>
#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "engine/cluster/motifs_json.h"
#include "engine/synth/truth_json_reader.h"

namespace motif {

namespace {

std::vector<std::string> SplitTabs(const std::string& line) {
  std::vector<std::string> fields;
  boost::algorithm::split(fields, line, [](char c) { return c == '\t'; });
  return fields;
}

bool ParseFrame(const std::string& text, uint64_t* frame) {
  const char* end = text.data() + text.size();
  auto [ptr, error] = std::from_chars(text.data(), end, *frame);
  return error == std::errc() && ptr == end && !text.empty();
}

// Another run's motifs as the truth: motif k becomes the movement "motif-k".
Result<std::vector<TruthOccurrence>> OccurrencesOfMotifs(const std::string& text,
                                                         const std::string& name) {
  MOTIF_ASSIGN_OR_RETURN(MotifsDocument document, ParseMotifsJson(text, name));
  std::vector<TruthOccurrence> occurrences;
  for (const MotifsJsonMotif& motif : document.motifs) {
    for (const MotifsJsonInstance& instance : motif.instances) {
      occurrences.push_back(
          {instance.clip, "motif-" + std::to_string(motif.id), instance.start, instance.end});
    }
  }
  return occurrences;
}

}  // namespace

Result<std::vector<TruthOccurrence>> ParseTruthTsv(const std::string& text,
                                                   const std::string& name) {
  std::istringstream lines(text);
  std::string line;
  uint64_t line_number = 0;
  bool header_seen = false;
  std::vector<TruthOccurrence> occurrences;
  while (std::getline(lines, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::string where = name + ": line " + std::to_string(line_number) + ": ";
    const std::vector<std::string> fields = SplitTabs(line);
    if (!header_seen) {
      if (fields != std::vector<std::string>{"clip", "movement", "start", "end"}) {
        return Status::InvalidArgument(where +
                                       "expected the header 'clip<TAB>movement<TAB>start<TAB>end'");
      }
      header_seen = true;
      continue;
    }
    if (fields.size() != 4) {
      return Status::InvalidArgument(where + "expected 4 tab-separated fields, found " +
                                     std::to_string(fields.size()));
    }
    TruthOccurrence occurrence{fields[0], fields[1], 0, 0};
    if (!ParseFrame(fields[2], &occurrence.start) || !ParseFrame(fields[3], &occurrence.end)) {
      return Status::InvalidArgument(where + "start and end must be frame numbers");
    }
    if (occurrence.clip.empty() || occurrence.movement.empty()) {
      return Status::InvalidArgument(where + "empty clip or movement");
    }
    if (occurrence.end <= occurrence.start) {
      return Status::InvalidArgument(where + "end must be greater than start");
    }
    occurrences.push_back(std::move(occurrence));
  }
  if (!header_seen) return Status::InvalidArgument(name + ": no header line");
  return occurrences;
}

Result<std::vector<TruthOccurrence>> ReadTruthOccurrences(const std::string& path) {
  if (path.size() >= 5 && path.compare(path.size() - 5, 5, ".json") == 0) {
    MOTIF_ASSIGN_OR_RETURN(std::string text, ReadFileToString(path));
    const nlohmann::json root = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (root.is_object() && root.contains("motifs") && !root.contains("instances")) {
      return OccurrencesOfMotifs(text, path);
    }
    MOTIF_ASSIGN_OR_RETURN(TruthFile truth, ParseTruthJson(text, path));
    std::vector<TruthOccurrence> occurrences;
    occurrences.reserve(truth.instances.size());
    for (const PlantedInstance& planted : truth.instances) {
      occurrences.push_back(
          {planted.clip, "planted-" + std::to_string(planted.motif), planted.start, planted.end});
    }
    return occurrences;
  }
  MOTIF_ASSIGN_OR_RETURN(std::string text, ReadFileToString(path));
  return ParseTruthTsv(text, path);
}

}  // namespace motif
