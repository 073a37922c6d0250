#include "engine/cluster/motifs_json.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
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
                              clip.first_frame, clip.source_first_frame, clip.source_fps});
  }
  for (size_t rank = 0; rank < result.motifs.size(); ++rank) {
    MotifsJsonMotif motif;
    motif.id = static_cast<uint32_t>(rank);
    const Motif& clustered = result.motifs[rank];
    const bool measured =
        !clustered.instances.empty() && clustered.distances.size() == clustered.instances.size();
    if (measured) motif.representative = clustered.representative;
    for (size_t inst = 0; inst < clustered.instances.size(); ++inst) {
      const MotifInstance& instance = result.instances[clustered.instances[inst]];
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
      if (measured) motif.instances.back().distance = clustered.distances[inst];
    }
    document.motifs.push_back(std::move(motif));
  }
  return document;
}

uint64_t FileFrameOf(const MotifsJsonClip& clip, uint64_t clip_frame) {
  if (clip.source_fps <= 0 || clip.fps <= 0 || clip.source_fps == clip.fps) {
    return clip.source_first_frame + clip_frame;
  }
  // k × source_fps first, then / fps: exact halves (3 × 100 / 120 = 2.5) stay halves.
  const double position = static_cast<double>(clip_frame) * clip.source_fps / clip.fps;
  return clip.source_first_frame + static_cast<uint64_t>(std::llround(position));
}

namespace {

using ClipsByName = std::unordered_map<std::string, const MotifsJsonClip*>;

Json ArchiveVersionJson(const MotifsArchiveVersion& archive_version) {
  char identity[17];
  std::snprintf(identity, sizeof identity, "%016" PRIx64, archive_version.identity);
  Json version;
  version["generation"] = archive_version.generation;
  version["committed_bytes"] = archive_version.committed_bytes;
  version["identity"] = identity;
  return version;
}

// "clips": one clip a line.
void AppendClipsText(const std::vector<MotifsJsonClip>& clips, std::string* text) {
  *text += "  \"clips\": [";
  for (size_t idx = 0; idx < clips.size(); ++idx) {
    const MotifsJsonClip& clip = clips[idx];
    Json entry;
    entry["name"] = clip.name;
    entry["source"] = clip.source;
    entry["frames"] = clip.frames;
    entry["fps"] = clip.fps;
    entry["first_frame"] = clip.first_frame;
    entry["source_first_frame"] = clip.source_first_frame;
    if (clip.source_fps > 0) entry["source_fps"] = clip.source_fps;
    *text += (idx == 0 ? "\n    " : ",\n    ") + Dump(entry);
  }
  *text += clips.empty() ? "],\n" : "\n  ],\n";
}

// The parameters; the shortest motif also in seconds at the first clip's rate.
Json ParamsJson(const MotifsDocument& document) {
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
  return params;
}

Json SummaryJson(const MotifsDocument& document) {
  uint64_t instance_count = 0;
  for (const MotifsJsonMotif& motif : document.motifs) instance_count += motif.instances.size();
  Json summary;
  summary["motifs"] = document.motifs.size();
  summary["instances"] = instance_count;
  summary["covered_frames"] = document.covered_frames;
  return summary;
}

// A motif's head: id, instance count, mean length (frames and seconds), score, representative.
Json MotifHeadJson(const MotifsJsonMotif& motif, const ClipsByName& clip_of) {
  uint64_t frames = 0;
  double seconds = 0;
  for (const MotifsJsonInstance& instance : motif.instances) {
    frames += instance.length();
    auto clip = clip_of.find(instance.clip);
    if (clip != clip_of.end() && clip->second->fps > 0) {
      seconds += static_cast<double>(instance.length()) / clip->second->fps;
    }
  }
  const double count = static_cast<double>(std::max<size_t>(1, motif.instances.size()));
  Json head;
  head["id"] = motif.id;
  head["instance_count"] = motif.instances.size();
  head["mean_length"] = static_cast<double>(frames) / count;
  head["mean_seconds"] = seconds / count;
  head["score"] = static_cast<double>(frames) * (count - 1) / count;  // RankMotifs' order
  if (motif.representative) head["representative"] = *motif.representative;
  return head;
}

// An instance: its clip frames, global frame and length, its file frames and its distance.
Json InstanceJson(const MotifsJsonInstance& instance, const ClipsByName& clip_of) {
  Json entry;
  entry["clip"] = instance.clip;
  entry["start"] = instance.start;
  entry["end"] = instance.end;
  entry["frame"] = instance.frame;
  entry["length"] = instance.length();
  auto clip = clip_of.find(instance.clip);
  if (clip != clip_of.end()) {
    entry["file_first_frame"] = FileFrameOf(*clip->second, instance.start);
    entry["file_last_frame"] = FileFrameOf(*clip->second, instance.end - 1);
  }
  if (instance.distance) entry["distance"] = *instance.distance;
  return entry;
}

// "motifs": a motif's head on its line, then one instance a line.
void AppendMotifsText(const MotifsDocument& document, std::string* text) {
  ClipsByName clip_of;
  for (const MotifsJsonClip& clip : document.clips) clip_of[clip.name] = &clip;
  *text += "  \"motifs\": [";
  for (size_t idx = 0; idx < document.motifs.size(); ++idx) {
    const MotifsJsonMotif& motif = document.motifs[idx];
    std::string head_text = Dump(MotifHeadJson(motif, clip_of));
    head_text.pop_back();  // reopen the object to append the instances array
    *text += (idx == 0 ? "\n    " : ",\n    ") + head_text + ", \"instances\": [";
    for (size_t inst = 0; inst < motif.instances.size(); ++inst) {
      *text += (inst == 0 ? "\n      " : ",\n      ") +
               Dump(InstanceJson(motif.instances[inst], clip_of));
    }
    *text += motif.instances.empty() ? "]}" : "\n    ]}";
  }
  *text += document.motifs.empty() ? "]\n" : "\n  ]\n";
}

}  // namespace

std::string MotifsJsonText(const MotifsDocument& document) {
  // One clip, and one instance, per line: readable and diffable with thousands of them.
  std::string text = "{\n";
  text += "  \"version\": 2,\n";
  text += "  \"archive\": " + Dump(document.archive) + ",\n";
  text += "  \"frames\": " + std::to_string(document.frames) + ",\n";
  if (document.archive_version.known()) {
    text += "  \"archive_version\": " + Dump(ArchiveVersionJson(document.archive_version)) + ",\n";
  }
  AppendClipsText(document.clips, &text);
  text += "  \"params\": " + Dump(ParamsJson(document)) + ",\n";
  text += "  \"summary\": " + Dump(SummaryJson(document)) + ",\n";
  AppendMotifsText(document, &text);
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

namespace {

using FirstFrames = std::unordered_map<std::string, uint64_t>;  // first archive frame by clip

Status ParseArchiveVersion(const Json& version, const std::string& where,
                           MotifsArchiveVersion* out) {
  if (!version.is_object()) return Status::InvalidArgument(where + " is not an object");
  MOTIF_RETURN_IF_ERROR(Get(version, "generation", where, &out->generation));
  MOTIF_RETURN_IF_ERROR(Get(version, "committed_bytes", where, &out->committed_bytes));
  std::string identity;
  MOTIF_RETURN_IF_ERROR(Get(version, "identity", where, &identity));
  char* end = nullptr;
  out->identity = std::strtoull(identity.c_str(), &end, 16);
  if (identity.size() != 16 || *end != '\0' || out->generation == 0) {
    return Status::InvalidArgument(where +
                                   ": \"identity\" must be 16 hex digits and "
                                   "\"generation\" at least 1");
  }
  return Status::Ok();
}

// The "clips" array, and each clip's first frame by name (for the instances' global frames).
Status ParseMotifsClips(const Json& clips, const std::string& name,
                        std::vector<MotifsJsonClip>* out, FirstFrames* first_frame_of) {
  for (size_t idx = 0; idx < clips.size(); ++idx) {
    const Json& entry = clips[idx];
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
    if (entry.contains("source_fps")) {
      MOTIF_RETURN_IF_ERROR(Get(entry, "source_fps", where, &clip.source_fps));
    }
    (*first_frame_of)[clip.name] = clip.first_frame;
    out->push_back(std::move(clip));
  }
  return Status::Ok();
}

// The "params" object; similarity and the pause fields are optional (older files).
Status ParseMotifsParams(const Json& params, const std::string& where, MotifsJsonParams* out) {
  MOTIF_RETURN_IF_ERROR(Get(params, "eps", where, &out->eps));
  MOTIF_RETURN_IF_ERROR(Get(params, "kmax", where, &out->kmax));
  MOTIF_RETURN_IF_ERROR(Get(params, "branch", where, &out->branch));
  MOTIF_RETURN_IF_ERROR(Get(params, "min_length", where, &out->min_length));
  MOTIF_RETURN_IF_ERROR(Get(params, "seed", where, &out->seed));
  if (params.contains("similarity")) {
    MOTIF_RETURN_IF_ERROR(Get(params, "similarity", where, &out->similarity));
  }
  if (params.contains("pause_speed")) {
    MOTIF_RETURN_IF_ERROR(Get(params, "pause_speed", where, &out->pause_speed));
    MOTIF_RETURN_IF_ERROR(Get(params, "pause_seconds", where, &out->pause_seconds));
  }
  if (params.contains("groups") && params["groups"].is_string() && params["groups"] == "auto") {
    out->groups = 0;
  } else {
    MOTIF_RETURN_IF_ERROR(Get(params, "groups", where + " (a number or \"auto\")", &out->groups));
  }
  return Status::Ok();
}

Result<MotifsJsonInstance> ParseMotifsInstance(const Json& item, const std::string& where,
                                               const FirstFrames& first_frame_of) {
  if (!item.is_object()) return Status::InvalidArgument(where + " is not an object");
  MotifsJsonInstance instance;
  MOTIF_RETURN_IF_ERROR(Get(item, "clip", where, &instance.clip));
  MOTIF_RETURN_IF_ERROR(Get(item, "start", where, &instance.start));
  MOTIF_RETURN_IF_ERROR(Get(item, "end", where, &instance.end));
  if (instance.end <= instance.start) {
    return Status::InvalidArgument(where + ": end must be after start");
  }
  auto clip = first_frame_of.find(instance.clip);
  if (clip == first_frame_of.end()) {
    return Status::InvalidArgument(where + ": unknown clip \"" + instance.clip + "\"");
  }
  instance.frame = clip->second + instance.start;
  if (item.contains("distance")) {
    double distance = 0;
    MOTIF_RETURN_IF_ERROR(Get(item, "distance", where, &distance));
    if (!(distance >= 0)) return Status::InvalidArgument(where + ": \"distance\" is negative");
    instance.distance = distance;
  }
  return instance;
}

// The optional "representative": an index into the instances, each of which then has a distance.
Status ParseRepresentative(const Json& entry, const std::string& where, MotifsJsonMotif* motif) {
  if (!entry.contains("representative")) return Status::Ok();
  uint64_t representative = 0;
  MOTIF_RETURN_IF_ERROR(Get(entry, "representative", where, &representative));
  if (representative >= motif->instances.size()) {
    return Status::InvalidArgument(where + ": \"representative\" is not an index of its instances");
  }
  for (size_t inst = 0; inst < motif->instances.size(); ++inst) {
    if (!motif->instances[inst].distance) {
      return Status::InvalidArgument(where + ".instances[" + std::to_string(inst) +
                                     "]: missing \"distance\" (the motif has a representative)");
    }
  }
  motif->representative = static_cast<uint32_t>(representative);
  return Status::Ok();
}

Result<MotifsJsonMotif> ParseMotifsMotif(const Json& entry, const std::string& where,
                                         const FirstFrames& first_frame_of) {
  if (!entry.is_object()) return Status::InvalidArgument(where + " is not an object");
  MotifsJsonMotif motif;
  MOTIF_RETURN_IF_ERROR(Get(entry, "id", where, &motif.id));
  if (!entry.contains("instances") || !entry["instances"].is_array()) {
    return Status::InvalidArgument(where + ": \"instances\" must be an array");
  }
  const Json& instances = entry["instances"];
  for (size_t inst = 0; inst < instances.size(); ++inst) {
    MOTIF_ASSIGN_OR_RETURN(
        MotifsJsonInstance instance,
        ParseMotifsInstance(instances[inst], where + ".instances[" + std::to_string(inst) + "]",
                            first_frame_of));
    motif.instances.push_back(std::move(instance));
  }
  MOTIF_RETURN_IF_ERROR(ParseRepresentative(entry, where, &motif));
  return motif;
}

// "clips" and "motifs" are arrays, "params" an object.
Status CheckMotifsShape(const Json& root, const std::string& name) {
  for (const char* key : {"clips", "motifs"}) {
    if (!root.contains(key) || !root[key].is_array()) {
      return Status::InvalidArgument(name + ": \"" + key + "\" must be an array");
    }
  }
  if (!root.contains("params") || !root["params"].is_object()) {
    return Status::InvalidArgument(name + ": \"params\" must be an object");
  }
  return Status::Ok();
}

}  // namespace

Result<MotifsDocument> ParseMotifsJson(const std::string& text, const std::string& name) {
  const Json root = Json::parse(text, nullptr, /*allow_exceptions=*/false);
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
    MOTIF_RETURN_IF_ERROR(ParseArchiveVersion(root["archive_version"], name + ": archive_version",
                                              &document.archive_version));
  }
  MOTIF_RETURN_IF_ERROR(CheckMotifsShape(root, name));
  FirstFrames first_frame_of;
  MOTIF_RETURN_IF_ERROR(ParseMotifsClips(root["clips"], name, &document.clips, &first_frame_of));
  MOTIF_RETURN_IF_ERROR(ParseMotifsParams(root["params"], name + ": params", &document.params));
  if (root.contains("summary") && root["summary"].is_object() &&
      root["summary"].contains("covered_frames") &&
      root["summary"]["covered_frames"].is_number_unsigned()) {
    document.covered_frames = root["summary"]["covered_frames"].get<uint64_t>();
  }
  const Json& motifs = root["motifs"];
  for (size_t idx = 0; idx < motifs.size(); ++idx) {
    MOTIF_ASSIGN_OR_RETURN(
        MotifsJsonMotif motif,
        ParseMotifsMotif(motifs[idx], name + ": motifs[" + std::to_string(idx) + "]",
                         first_frame_of));
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
