#include "engine/pipeline/run_record.h"

#include <filesystem>

#include <nlohmann/json.hpp>

#include "common/byte_coding.h"
#include "common/file_util.h"

namespace motif {

namespace {

constexpr int kRunRecordVersion = 1;

std::filesystem::path FolderOf(const std::string& path) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  return folder.empty() ? std::filesystem::path(".") : folder;
}

}  // namespace

Status WriteRunRecord(const std::string& path, const RunRecord& record) {
  nlohmann::json json;
  json["version"] = kRunRecordVersion;
  json["motifs_checksum"] = Hex(record.motifs_checksum);
  json["parameters"] = record.parameters_text;
  json["timings"] = nlohmann::json::array();
  for (const RunStageTiming& timing : record.timings) {
    json["timings"].push_back(
        {{"stage", timing.stage}, {"seconds", timing.seconds}, {"reused", timing.reused}});
  }
  json["total_seconds"] = record.total_seconds;
  json["peak_memory_bytes"] = record.peak_memory_bytes;
  json["truth"] = record.truth_path;
  if (!record.descriptions.empty()) json["descriptions"] = record.descriptions;
  return AtomicWriteFile(path, json.dump(2) + "\n");
}

Result<RunRecord> ReadRunRecord(const std::string& path, const std::string& motifs_path) {
  MOTIF_ASSIGN_OR_RETURN(std::string text, ReadFileToString(path));
  MOTIF_ASSIGN_OR_RETURN(std::string motifs, ReadFileToString(motifs_path));
  const nlohmann::json json = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  const auto malformed = [&](const std::string& why) {
    return Status::InvalidArgument(path + ": " + why);
  };
  if (!json.is_object() || json.value("version", 0) != kRunRecordVersion) {
    return malformed("not a version 1 run record");
  }
  RunRecord record;
  record.motifs_checksum = Checksum64(motifs.data(), motifs.size());
  if (json.value("motifs_checksum", std::string()) != Hex(record.motifs_checksum)) {
    return malformed("describes another version of " + motifs_path);
  }
  try {
    record.parameters_text = json.at("parameters").get<std::string>();
    for (const nlohmann::json& timing : json.at("timings")) {
      record.timings.push_back({timing.at("stage").get<std::string>(),
                                timing.at("seconds").get<double>(),
                                timing.at("reused").get<bool>()});
    }
    record.total_seconds = json.at("total_seconds").get<double>();
    record.peak_memory_bytes = json.at("peak_memory_bytes").get<uint64_t>();
    if (json.contains("descriptions")) {
      record.descriptions = json.at("descriptions").get<std::map<std::string, std::string>>();
    }
    const std::string truth = json.at("truth").get<std::string>();
    if (!truth.empty()) {
      record.truth_path = std::filesystem::path(truth).is_absolute()
                              ? truth
                              : (FolderOf(path) / truth).lexically_normal().string();
    }
  } catch (const nlohmann::json::exception& error) {
    return malformed(error.what());
  }
  return record;
}

}  // namespace motif
