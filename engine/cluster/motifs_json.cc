#include "engine/cluster/motifs_json.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "common/file_util.h"

namespace motif {

namespace {

using Json = nlohmann::ordered_json;
constexpr auto kReplace = Json::error_handler_t::replace;

std::string Dump(const Json& json) { return json.dump(-1, ' ', false, kReplace); }

// Reads a required field of the given JSON type, naming it in the error.
template <typename T>
Status Get(const Json& object, const char* key, const std::string& where, T* out) {
  auto it = object.find(key);
  if (it == object.end()) return Status::InvalidArgument(where + ": missing \"" + key + "\"");
  bool type_ok = false;
  if constexpr (std::is_same_v<T, std::string>) {
    type_ok = it->is_string();
  } else if constexpr (std::is_floating_point_v<T>) {
    type_ok = it->is_number();
  } else {
    type_ok =
        it->is_number_unsigned() || (it->is_number_integer() && it->template get<int64_t>() >= 0);
  }
  if (!type_ok) return Status::InvalidArgument(where + ": \"" + key + "\" has the wrong type");
  *out = it->template get<T>();
  return Status::Ok();
}

}  // namespace

Result<MotifsDocument> MakeMotifsDocument(const ClusterResult& result,
                                          const std::string& archive_path, uint64_t archive_frames,
                                          const std::vector<ClipInfo>& clips,
                                          const MotifsJsonParams& params) {
  MotifsDocument document;
  document.archive = archive_path;
  document.frames = archive_frames;
  document.params = params;
  document.covered_frames = result.report.covered_frames;
  for (const ClipInfo& clip : clips) {
    document.clips.push_back({clip.name, clip.source_path, clip.frame_count, clip.fps,
                              clip.first_frame, clip.source_first_frame});
  }
  for (size_t rank = 0; rank < result.motifs.size(); ++rank) {
    MotifsJsonMotif motif;
    motif.id = static_cast<uint32_t>(rank);
    for (uint32_t id : result.motifs[rank].instances) {
      const MotifInstance& instance = result.instances[id];
      auto clip = std::upper_bound(
          clips.begin(), clips.end(), instance.start,
          [](uint64_t frame, const ClipInfo& info) { return frame < info.first_frame; });
      if (clip == clips.begin() ||
          instance.end > std::prev(clip)->first_frame + std::prev(clip)->frame_count) {
        return Status::InvalidArgument("instance [" + std::to_string(instance.start) + ", " +
                                       std::to_string(instance.end) +
                                       ") is not inside one clip of " + archive_path);
      }
      --clip;
      motif.instances.push_back({clip->name, instance.start - clip->first_frame,
                                 instance.end - clip->first_frame, instance.start});
    }
    document.motifs.push_back(std::move(motif));
  }
  return document;
}

std::string MotifsJsonText(const MotifsDocument& document) {
  std::unordered_map<std::string, double> fps_of;
  for (const MotifsJsonClip& clip : document.clips) fps_of[clip.name] = clip.fps;
  uint64_t instance_count = 0;
  for (const MotifsJsonMotif& motif : document.motifs) instance_count += motif.instances.size();

  // One clip, and one instance, per line: readable and diffable with thousands of them.
  std::string text = "{\n";
  text += "  \"version\": 2,\n";
  text += "  \"archive\": " + Dump(document.archive) + ",\n";
  text += "  \"frames\": " + std::to_string(document.frames) + ",\n";
  if (document.archive_version.known()) {
    char identity[17];
    std::snprintf(identity, sizeof identity, "%016" PRIx64, document.archive_version.identity);
    Json version;
    version["generation"] = document.archive_version.generation;
    version["committed_bytes"] = document.archive_version.committed_bytes;
    version["identity"] = identity;
    text += "  \"archive_version\": " + Dump(version) + ",\n";
  }
  text += "  \"clips\": [";
  for (size_t idx = 0; idx < document.clips.size(); ++idx) {
    const MotifsJsonClip& clip = document.clips[idx];
    Json entry;
    entry["name"] = clip.name;
    entry["source"] = clip.source;
    entry["frames"] = clip.frames;
    entry["fps"] = clip.fps;
    entry["first_frame"] = clip.first_frame;
    entry["source_first_frame"] = clip.source_first_frame;
    text += (idx == 0 ? "\n    " : ",\n    ") + Dump(entry);
  }
  text += document.clips.empty() ? "],\n" : "\n  ],\n";
  Json params;
  params["eps"] = document.params.eps;
  params["kmax"] = document.params.kmax;
  params["branch"] = document.params.branch;
  params["min_length"] = document.params.min_length;
  if (!document.clips.empty() && document.clips.front().fps > 0) {
    params["min_length_seconds"] =
        static_cast<double>(document.params.min_length) / document.clips.front().fps;
  }
  if (document.params.groups == 0) {
    params["groups"] = "auto";
  } else {
    params["groups"] = document.params.groups;
  }
  params["seed"] = document.params.seed;
  params["similarity"] = document.params.similarity;
  params["pause_speed"] = document.params.pause_speed;
  params["pause_seconds"] = document.params.pause_seconds;
  text += "  \"params\": " + Dump(params) + ",\n";
  Json summary;
  summary["motifs"] = document.motifs.size();
  summary["instances"] = instance_count;
  summary["covered_frames"] = document.covered_frames;
  text += "  \"summary\": " + Dump(summary) + ",\n";
  text += "  \"motifs\": [";
  for (size_t idx = 0; idx < document.motifs.size(); ++idx) {
    const MotifsJsonMotif& motif = document.motifs[idx];
    uint64_t frames = 0;
    double seconds = 0;
    for (const MotifsJsonInstance& instance : motif.instances) {
      frames += instance.length();
      auto fps = fps_of.find(instance.clip);
      if (fps != fps_of.end() && fps->second > 0) {
        seconds += static_cast<double>(instance.length()) / fps->second;
      }
    }
    const double count = static_cast<double>(std::max<size_t>(1, motif.instances.size()));
    Json head;
    head["id"] = motif.id;
    head["instance_count"] = motif.instances.size();
    head["mean_length"] = static_cast<double>(frames) / count;
    head["mean_seconds"] = seconds / count;
    head["score"] = static_cast<double>(frames) * (count - 1) / count;  // RankMotifs' order
    std::string head_text = Dump(head);
    head_text.pop_back();  // reopen the object to append the instances array
    text += (idx == 0 ? "\n    " : ",\n    ") + head_text + ", \"instances\": [";
    for (size_t inst = 0; inst < motif.instances.size(); ++inst) {
      const MotifsJsonInstance& instance = motif.instances[inst];
      Json entry;
      entry["clip"] = instance.clip;
      entry["start"] = instance.start;
      entry["end"] = instance.end;
      entry["frame"] = instance.frame;
      entry["length"] = instance.length();
      text += (inst == 0 ? "\n      " : ",\n      ") + Dump(entry);
    }
    text += motif.instances.empty() ? "]}" : "\n    ]}";
  }
  text += document.motifs.empty() ? "]\n" : "\n  ]\n";
  text += "}\n";
  return text;
}

namespace {

std::filesystem::path FolderOf(const std::string& motifs_path) {
  const std::filesystem::path folder = std::filesystem::path(motifs_path).parent_path();
  return folder.empty() ? std::filesystem::path(".") : folder;
}

// The archive path as stored in the file at `motifs_path`: relative to its folder, unless absolute.
std::string StoredArchivePath(const std::string& archive, const std::string& motifs_path) {
  const std::filesystem::path given(archive);
  if (given.is_absolute() || archive.empty()) return archive;
  std::error_code error;
  const std::filesystem::path relative =
      std::filesystem::relative(std::filesystem::absolute(given, error),
                                std::filesystem::absolute(FolderOf(motifs_path)), error);
  return error || relative.empty() ? archive : relative.string();
}

}  // namespace

Status WriteMotifsJson(const std::string& path, const MotifsDocument& document) {
  MotifsDocument stored = document;
  stored.archive = StoredArchivePath(document.archive, path);
  Status status = AtomicWriteFile(path, MotifsJsonText(stored));
  return status.ok() ? status : status.WithContext("motifs file " + path);
}

Result<MotifsDocument> ParseMotifsJson(const std::string& text, const std::string& name) {
  Json root = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (root.is_discarded() || !root.is_object()) {
    return Status::InvalidArgument(name + ": not a JSON object");
  }
  uint64_t version = 0;
  MOTIF_RETURN_IF_ERROR(Get(root, "version", name, &version));
  if (version != 1 && version != 2) {
    return Status::NotSupported(name + ": motifs.json version " + std::to_string(version) +
                                " (this reader knows versions 1 and 2)");
  }
  MotifsDocument document;
  document.archive_relative_to_file = version >= 2;
  MOTIF_RETURN_IF_ERROR(Get(root, "archive", name, &document.archive));
  MOTIF_RETURN_IF_ERROR(Get(root, "frames", name, &document.frames));
  if (root.contains("archive_version")) {
    const Json& version = root["archive_version"];
    const std::string where = name + ": archive_version";
    if (!version.is_object()) return Status::InvalidArgument(where + " is not an object");
    MotifsArchiveVersion& out = document.archive_version;
    MOTIF_RETURN_IF_ERROR(Get(version, "generation", where, &out.generation));
    MOTIF_RETURN_IF_ERROR(Get(version, "committed_bytes", where, &out.committed_bytes));
    std::string identity;
    MOTIF_RETURN_IF_ERROR(Get(version, "identity", where, &identity));
    char* end = nullptr;
    out.identity = std::strtoull(identity.c_str(), &end, 16);
    if (identity.size() != 16 || *end != '\0' || out.generation == 0) {
      return Status::InvalidArgument(where +
                                     ": \"identity\" must be 16 hex digits and "
                                     "\"generation\" at least 1");
    }
  }
  for (const char* key : {"clips", "motifs"}) {
    if (!root.contains(key) || !root[key].is_array()) {
      return Status::InvalidArgument(name + ": \"" + key + "\" must be an array");
    }
  }
  if (!root.contains("params") || !root["params"].is_object()) {
    return Status::InvalidArgument(name + ": \"params\" must be an object");
  }
  std::unordered_map<std::string, uint64_t> first_frame_of;
  for (size_t idx = 0; idx < root["clips"].size(); ++idx) {
    const Json& entry = root["clips"][idx];
    const std::string where = name + ": clips[" + std::to_string(idx) + "]";
    if (!entry.is_object()) return Status::InvalidArgument(where + " is not an object");
    MotifsJsonClip clip;
    MOTIF_RETURN_IF_ERROR(Get(entry, "name", where, &clip.name));
    MOTIF_RETURN_IF_ERROR(Get(entry, "source", where, &clip.source));
    MOTIF_RETURN_IF_ERROR(Get(entry, "frames", where, &clip.frames));
    MOTIF_RETURN_IF_ERROR(Get(entry, "fps", where, &clip.fps));
    MOTIF_RETURN_IF_ERROR(Get(entry, "first_frame", where, &clip.first_frame));
    if (entry.contains("source_first_frame")) {
      MOTIF_RETURN_IF_ERROR(Get(entry, "source_first_frame", where, &clip.source_first_frame));
    }
    first_frame_of[clip.name] = clip.first_frame;
    document.clips.push_back(std::move(clip));
  }
  const Json& params = root["params"];
  const std::string params_where = name + ": params";
  MOTIF_RETURN_IF_ERROR(Get(params, "eps", params_where, &document.params.eps));
  MOTIF_RETURN_IF_ERROR(Get(params, "kmax", params_where, &document.params.kmax));
  MOTIF_RETURN_IF_ERROR(Get(params, "branch", params_where, &document.params.branch));
  MOTIF_RETURN_IF_ERROR(Get(params, "min_length", params_where, &document.params.min_length));
  MOTIF_RETURN_IF_ERROR(Get(params, "seed", params_where, &document.params.seed));
  if (params.contains("similarity")) {
    MOTIF_RETURN_IF_ERROR(Get(params, "similarity", params_where, &document.params.similarity));
  }
  if (params.contains("pause_speed")) {
    MOTIF_RETURN_IF_ERROR(Get(params, "pause_speed", params_where, &document.params.pause_speed));
    MOTIF_RETURN_IF_ERROR(
        Get(params, "pause_seconds", params_where, &document.params.pause_seconds));
  }
  if (params.contains("groups") && params["groups"].is_string() && params["groups"] == "auto") {
    document.params.groups = 0;
  } else {
    MOTIF_RETURN_IF_ERROR(
        Get(params, "groups", params_where + " (a number or \"auto\")", &document.params.groups));
  }
  if (root.contains("summary") && root["summary"].is_object() &&
      root["summary"].contains("covered_frames") &&
      root["summary"]["covered_frames"].is_number_unsigned()) {
    document.covered_frames = root["summary"]["covered_frames"].get<uint64_t>();
  }
  for (size_t idx = 0; idx < root["motifs"].size(); ++idx) {
    const Json& entry = root["motifs"][idx];
    const std::string where = name + ": motifs[" + std::to_string(idx) + "]";
    if (!entry.is_object()) return Status::InvalidArgument(where + " is not an object");
    MotifsJsonMotif motif;
    MOTIF_RETURN_IF_ERROR(Get(entry, "id", where, &motif.id));
    if (!entry.contains("instances") || !entry["instances"].is_array()) {
      return Status::InvalidArgument(where + ": \"instances\" must be an array");
    }
    for (size_t inst = 0; inst < entry["instances"].size(); ++inst) {
      const Json& item = entry["instances"][inst];
      const std::string item_where = where + ".instances[" + std::to_string(inst) + "]";
      if (!item.is_object()) return Status::InvalidArgument(item_where + " is not an object");
      MotifsJsonInstance instance;
      MOTIF_RETURN_IF_ERROR(Get(item, "clip", item_where, &instance.clip));
      MOTIF_RETURN_IF_ERROR(Get(item, "start", item_where, &instance.start));
      MOTIF_RETURN_IF_ERROR(Get(item, "end", item_where, &instance.end));
      if (instance.end <= instance.start) {
        return Status::InvalidArgument(item_where + ": end must be after start");
      }
      auto clip = first_frame_of.find(instance.clip);
      if (clip == first_frame_of.end()) {
        return Status::InvalidArgument(item_where + ": unknown clip \"" + instance.clip + "\"");
      }
      instance.frame = clip->second + instance.start;
      motif.instances.push_back(std::move(instance));
    }
    document.motifs.push_back(std::move(motif));
  }
  return document;
}

Result<MotifsDocument> ReadMotifsJson(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(std::string text, ReadFileToString(path));
  MOTIF_ASSIGN_OR_RETURN(MotifsDocument document, ParseMotifsJson(text, path));
  ResolveArchivePath(path, &document);
  return document;
}

void ResolveArchivePath(const std::string& motifs_path, MotifsDocument* document) {
  if (!document->archive_relative_to_file || document->archive.empty() ||
      std::filesystem::path(document->archive).is_absolute()) {
    return;
  }
  document->archive = (FolderOf(motifs_path) / document->archive).lexically_normal().string();
  document->archive_relative_to_file = false;
}

}  // namespace motif
