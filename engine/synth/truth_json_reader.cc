#include "engine/synth/truth_json_reader.h"

#include <filesystem>

#include <nlohmann/json.hpp>

#include "common/file_util.h"

namespace motif {

namespace {

using Json = nlohmann::json;

bool IsCount(const Json& value) {
  return value.is_number_unsigned() || (value.is_number_integer() && value.get<int64_t>() >= 0);
}

Status Require(const Json& object, const char* key, bool ok, const std::string& where) {
  if (!object.contains(key)) return Status::InvalidArgument(where + ": missing \"" + key + "\"");
  if (!ok) return Status::InvalidArgument(where + ": \"" + key + "\" has the wrong type");
  return Status::Ok();
}

}  // namespace

Result<TruthFile> ParseTruthJson(const std::string& text, const std::string& name) {
  Json root = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (root.is_discarded() || !root.is_object()) {
    return Status::InvalidArgument(name + ": not a JSON object");
  }
  MOTIF_RETURN_IF_ERROR(Require(root, "version", IsCount(root.value("version", Json())), name));
  if (root["version"].get<uint64_t>() != 1) {
    return Status::NotSupported(name + ": truth file version " + root["version"].dump() +
                                " (this reader knows version 1)");
  }
  TruthFile truth;
  MOTIF_RETURN_IF_ERROR(Require(root, "archive", root.value("archive", Json()).is_string(), name));
  MOTIF_RETURN_IF_ERROR(Require(root, "frames", IsCount(root.value("frames", Json())), name));
  MOTIF_RETURN_IF_ERROR(
      Require(root, "instances", root.value("instances", Json()).is_array(), name));
  truth.archive = root["archive"].get<std::string>();
  truth.frames = root["frames"].get<uint64_t>();
  if (root.contains("seed") && IsCount(root["seed"])) truth.seed = root["seed"].get<uint64_t>();
  if (root.contains("motifs") && IsCount(root["motifs"])) {
    truth.motifs = root["motifs"].get<uint32_t>();
  }
  const Json& instances = root["instances"];
  for (size_t idx = 0; idx < instances.size(); ++idx) {
    const Json& entry = instances[idx];
    const std::string where = name + ": instances[" + std::to_string(idx) + "]";
    if (!entry.is_object()) return Status::InvalidArgument(where + " is not an object");
    MOTIF_RETURN_IF_ERROR(Require(entry, "clip", entry.value("clip", Json()).is_string(), where));
    for (const char* key : {"start", "end", "motif"}) {
      MOTIF_RETURN_IF_ERROR(Require(entry, key, IsCount(entry.value(key, Json())), where));
    }
    PlantedInstance instance;
    instance.clip = entry["clip"].get<std::string>();
    instance.start = entry["start"].get<uint64_t>();
    instance.end = entry["end"].get<uint64_t>();
    instance.motif = entry["motif"].get<uint32_t>();
    if (entry.contains("warp") && entry["warp"].is_number()) {
      instance.warp = entry["warp"].get<double>();
    }
    if (entry.contains("nonuniform") && entry["nonuniform"].is_boolean()) {
      instance.nonuniform = entry["nonuniform"].get<bool>();
    }
    if (instance.end <= instance.start) {
      return Status::InvalidArgument(where + ": end must be after start");
    }
    truth.instances.push_back(std::move(instance));
  }
  return truth;
}

Result<TruthFile> ReadTruthJson(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(std::string text, ReadFileToString(path));
  return ParseTruthJson(text, path);
}

std::string TruthPathFor(const std::string& archive_path) {
  std::filesystem::path path(archive_path);
  if (path.extension() == ".mfs") path.replace_extension("");
  return path.string() + ".truth.json";
}

}  // namespace motif
