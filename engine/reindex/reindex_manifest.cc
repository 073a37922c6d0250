#include "engine/reindex/reindex_manifest.h"

#include <cinttypes>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "common/file_util.h"

namespace motif {
namespace {

using nlohmann::json;

constexpr char kFormatName[] = "motifmine reindex manifest";
constexpr int kFormatVersion = 1;

std::string Hex64(uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016" PRIx64, value);
  return text;
}

json FileJson(const VersionFile& file) {
  return {{"path", file.path}, {"bytes", file.bytes}, {"checksum", Hex64(file.checksum)}};
}

json LshJson(const LshOptions& lsh) {
  return {{"tables", lsh.tables},
          {"hashes", lsh.hashes_per_table},
          {"width", lsh.bucket_width},
          {"width_per_hash", lsh.width_per_hash},
          {"probes", lsh.probes_per_table},
          {"max_candidates", lsh.max_candidates},
          {"max_bucket_scan", lsh.max_bucket_scan},
          {"ranking", LshRankingName(lsh.ranking)},
          {"max_entries", lsh.max_entries},
          {"first_round_scan", lsh.first_round_scan},
          {"extension_stages", lsh.extension_stages},
          {"sparse_radius_factor", lsh.sparse_radius_factor},
          {"chain", lsh.chain_columns},
          {"chain_advance", lsh.chain_advance},
          {"chain_probe_every", lsh.chain_probe_every},
          {"chained_max_candidates", lsh.chained_max_candidates},
          {"chain_sweeps", lsh.chain_sweeps},
          {"seed", lsh.seed},
          {"shard_frames", lsh.shard_frames}};
}

// Reads fields of one JSON object, recording the first problem (the field's full name).
class Fields {
 public:
  Fields(const json& object, std::string where, std::string* problem)
      : object_(object), where_(std::move(where)), problem_(problem) {
    if (!object_.is_object() && problem_->empty()) *problem_ = where_ + ": not an object";
  }

  template <typename T>
  T Get(const char* name) {
    if (!problem_->empty() || !object_.is_object()) return T{};
    const auto found = object_.find(name);
    if (found == object_.end()) {
      *problem_ = where_ + ": missing \"" + name + "\"";
      return T{};
    }
    try {
      if constexpr (std::is_same_v<T, bool>) {
        if (!found->is_boolean()) throw std::invalid_argument("not a boolean");
      } else if constexpr (std::is_arithmetic_v<T>) {
        if (!found->is_number()) throw std::invalid_argument("not a number");
        if constexpr (std::is_unsigned_v<T>) {
          if (found->is_number_float() || found->template get<int64_t>() < 0 ||
              found->template get<uint64_t>() >
                  static_cast<uint64_t>(std::numeric_limits<T>::max())) {
            throw std::invalid_argument("not an unsigned integer of the field's size");
          }
        }
      } else if constexpr (std::is_same_v<T, std::string>) {
        if (!found->is_string()) throw std::invalid_argument("not a string");
      }
      return found->template get<T>();
    } catch (const std::exception& error) {
      *problem_ = where_ + ": \"" + name + "\" is " + error.what();
      return T{};
    }
  }

  // Get, or `fallback` when the field is absent.
  template <typename T>
  T GetOr(const char* name, T fallback) {
    if (object_.is_object() && object_.find(name) == object_.end()) return fallback;
    return Get<T>(name);
  }

  uint64_t GetHex(const char* name) {
    const std::string text = Get<std::string>(name);
    if (!problem_->empty()) return 0;
    char* end = nullptr;
    const uint64_t value = std::strtoull(text.c_str(), &end, 16);
    if (text.size() != 16 || *end != '\0') {
      *problem_ = where_ + ": \"" + name + "\" is not 16 hex digits";
      return 0;
    }
    return value;
  }

  const json& Object(const char* name) {
    static const json kNull;
    if (!problem_->empty() || !object_.is_object()) return kNull;
    const auto found = object_.find(name);
    if (found == object_.end()) {
      *problem_ = where_ + ": missing \"" + name + "\"";
      return kNull;
    }
    return *found;
  }

  std::string Sub(const char* name) const { return where_ + "." + name; }

 private:
  const json& object_;
  std::string where_;
  std::string* problem_;
};

VersionFile ParseFile(const json& object, const std::string& where, std::string* problem) {
  Fields fields(object, where, problem);
  VersionFile file;
  file.path = fields.Get<std::string>("path");
  file.bytes = fields.Get<uint64_t>("bytes");
  file.checksum = fields.GetHex("checksum");
  return file;
}

LshOptions ParseLsh(const json& object, const std::string& where, std::string* problem) {
  Fields fields(object, where, problem);
  LshOptions lsh;
  lsh.tables = fields.Get<uint32_t>("tables");
  lsh.hashes_per_table = fields.Get<uint32_t>("hashes");
  lsh.bucket_width = fields.Get<float>("width");
  lsh.width_per_hash = fields.Get<float>("width_per_hash");
  lsh.probes_per_table = fields.Get<uint32_t>("probes");
  lsh.max_candidates = fields.Get<uint32_t>("max_candidates");
  lsh.max_bucket_scan = fields.Get<uint32_t>("max_bucket_scan");
  const std::string ranking = fields.Get<std::string>("ranking");
  if (problem->empty() && !ParseLshRanking(ranking, &lsh.ranking)) {
    *problem = where + ": \"ranking\" is neither sort nor code";
  }
  lsh.max_entries = fields.Get<uint32_t>("max_entries");
  lsh.first_round_scan = fields.Get<uint32_t>("first_round_scan");
  lsh.extension_stages = fields.Get<uint32_t>("extension_stages");
  lsh.sparse_radius_factor = fields.Get<float>("sparse_radius_factor");
  lsh.chain_columns = fields.Get<uint32_t>("chain");
  lsh.chain_advance = fields.Get<uint32_t>("chain_advance");
  // Absent from manifests written before it existed, whose columns all probed.
  lsh.chain_probe_every = fields.GetOr<uint32_t>("chain_probe_every", 1);
  lsh.chained_max_candidates = fields.Get<uint32_t>("chained_max_candidates");
  lsh.chain_sweeps = fields.Get<uint32_t>("chain_sweeps");
  lsh.seed = fields.Get<uint64_t>("seed");
  lsh.shard_frames = fields.Get<uint32_t>("shard_frames");
  return lsh;
}

}  // namespace

bool SameLshFamily(const LshOptions& a, const LshOptions& b) {
  return a.tables == b.tables && a.hashes_per_table == b.hashes_per_table &&
         a.bucket_width == b.bucket_width && a.width_per_hash == b.width_per_hash &&
         a.probes_per_table == b.probes_per_table && a.max_candidates == b.max_candidates &&
         a.max_bucket_scan == b.max_bucket_scan && a.ranking == b.ranking &&
         a.max_entries == b.max_entries && a.first_round_scan == b.first_round_scan &&
         a.extension_stages == b.extension_stages &&
         a.sparse_radius_factor == b.sparse_radius_factor && a.chain_columns == b.chain_columns &&
         a.chain_advance == b.chain_advance && a.chain_probe_every == b.chain_probe_every &&
         a.chained_max_candidates == b.chained_max_candidates && a.chain_sweeps == b.chain_sweeps &&
         a.seed == b.seed && a.shard_frames == b.shard_frames;
}

bool MiningParams::operator==(const MiningParams& other) const {
  return eps == other.eps && eps_estimated == other.eps_estimated && mu == other.mu &&
         sigma == other.sigma && eps_rule == other.eps_rule &&
         eps_angle_degrees == other.eps_angle_degrees && k_max == other.k_max &&
         exclusion_frames == other.exclusion_frames && exact == other.exact &&
         (exact || SameLshFamily(lsh, other.lsh)) && seed == other.seed &&
         weights_path == other.weights_path && weights_hash == other.weights_hash &&
         block_columns == other.block_columns && branch == other.branch &&
         min_length == other.min_length && groups == other.groups && max_ncut == other.max_ncut &&
         min_similarity == other.min_similarity && max_length_ratio == other.max_length_ratio &&
         similarity == other.similarity && pause_speed == other.pause_speed &&
         pause_seconds == other.pause_seconds;
}

std::string VersionDirName(uint64_t version) {
  char name[32];
  std::snprintf(name, sizeof name, "v%06" PRIu64, version);
  return name;
}

std::string ManifestPath(const std::string& out_dir) {
  return (std::filesystem::path(out_dir) / "manifest.json").string();
}

std::string ManifestText(const ReindexManifest& manifest) {
  const MiningParams& params = manifest.params;
  json document = {{"format", kFormatName},
                   {"format_version", kFormatVersion},
                   {"version", manifest.version},
                   {"dir", manifest.dir},
                   {"written", manifest.written},
                   {"archive",
                    {{"path", manifest.archive.path},
                     {"generation", manifest.archive.generation},
                     {"committed_bytes", manifest.archive.committed_bytes},
                     {"identity", Hex64(manifest.archive.identity)},
                     {"frames", manifest.archive.frames},
                     {"clips", manifest.archive.clips}}},
                   {"params",
                    {{"eps", params.eps},
                     {"eps_estimated", params.eps_estimated},
                     {"mu", params.mu},
                     {"sigma", params.sigma},
                     {"eps_rule", params.eps_rule},
                     {"eps_angle", params.eps_angle_degrees},
                     {"kmax", params.k_max},
                     {"exclusion", params.exclusion_frames},
                     {"search", params.exact ? "exact" : "lsh"},
                     {"lsh", LshJson(params.lsh)},
                     {"seed", params.seed},
                     {"weights", params.weights_path},
                     {"weights_hash", Hex64(params.weights_hash)},
                     {"block_columns", params.block_columns},
                     {"branch", params.branch},
                     {"min_length", params.min_length},
                     {"groups", params.groups},
                     {"max_ncut", params.max_ncut},
                     {"min_similarity", params.min_similarity},
                     {"max_length_ratio", params.max_length_ratio},
                     {"similarity", params.similarity},
                     {"pause_speed", params.pause_speed},
                     {"pause_seconds", params.pause_seconds}}},
                   {"files",
                    {{"trellis", FileJson(manifest.trellis)},
                     {"paths", FileJson(manifest.paths)},
                     {"motifs", FileJson(manifest.motifs)},
                     {"report", FileJson(manifest.report)}}},
                   {"build",
                    {{"kind", manifest.build.kind},
                     {"previous_version", manifest.build.previous_version},
                     {"new_takes", manifest.build.new_takes},
                     {"new_frames", manifest.build.new_frames},
                     {"changed_columns", manifest.build.changed_columns},
                     {"copied_blocks", manifest.build.copied_blocks},
                     {"rewritten_blocks", manifest.build.rewritten_blocks},
                     {"seconds", manifest.build.seconds}}}};
  return document.dump(2) + "\n";
}

Result<ReindexManifest> ParseManifest(const std::string& text, const std::string& name) {
  const json document = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded() || !document.is_object()) {
    return Status::InvalidArgument(name + ": not a JSON object");
  }
  std::string problem;
  Fields top(document, name, &problem);
  const std::string format = top.Get<std::string>("format");
  const uint64_t format_version = top.Get<uint64_t>("format_version");
  if (problem.empty() && format != kFormatName) {
    return Status::InvalidArgument(name + ": \"format\" is not \"" + kFormatName + "\"");
  }
  if (problem.empty() && format_version != kFormatVersion) {
    return Status::NotSupported(name + ": manifest format version " +
                                std::to_string(format_version) + " (this reader knows " +
                                std::to_string(kFormatVersion) + ")");
  }
  ReindexManifest manifest;
  manifest.version = top.Get<uint64_t>("version");
  manifest.dir = top.Get<std::string>("dir");
  manifest.written = top.Get<std::string>("written");
  {
    Fields archive(top.Object("archive"), top.Sub("archive"), &problem);
    manifest.archive.path = archive.Get<std::string>("path");
    manifest.archive.generation = archive.Get<uint64_t>("generation");
    manifest.archive.committed_bytes = archive.Get<uint64_t>("committed_bytes");
    manifest.archive.identity = archive.GetHex("identity");
    manifest.archive.frames = archive.Get<uint64_t>("frames");
    manifest.archive.clips = archive.Get<uint64_t>("clips");
  }
  {
    const std::string where = top.Sub("params");
    Fields params(top.Object("params"), where, &problem);
    MiningParams& out = manifest.params;
    out.eps = params.Get<float>("eps");
    out.eps_estimated = params.Get<bool>("eps_estimated");
    out.mu = params.Get<float>("mu");
    out.sigma = params.Get<float>("sigma");
    out.eps_rule = params.GetOr<std::string>("eps_rule", "");  // absent before the rule flags
    out.eps_angle_degrees = params.GetOr<double>("eps_angle", 0);
    if (problem.empty() && !out.eps_rule.empty() && out.eps_rule != "joint-angle" &&
        out.eps_rule != "paper") {
      problem = where + ": \"eps_rule\" is neither joint-angle nor paper";
    }
    out.k_max = params.Get<uint32_t>("kmax");
    out.exclusion_frames = params.Get<uint32_t>("exclusion");
    const std::string search = params.Get<std::string>("search");
    if (problem.empty() && search != "exact" && search != "lsh") {
      problem = where + ": \"search\" is neither exact nor lsh";
    }
    out.exact = search == "exact";
    out.lsh = ParseLsh(params.Object("lsh"), params.Sub("lsh"), &problem);
    out.seed = params.Get<uint64_t>("seed");
    out.weights_path = params.Get<std::string>("weights");
    out.weights_hash = params.GetHex("weights_hash");
    out.block_columns = params.Get<uint32_t>("block_columns");
    out.branch = params.Get<uint32_t>("branch");
    out.min_length = params.Get<uint64_t>("min_length");
    out.groups = params.Get<uint32_t>("groups");
    out.max_ncut = params.Get<double>("max_ncut");
    out.min_similarity = params.Get<double>("min_similarity");
    out.max_length_ratio = params.Get<double>("max_length_ratio");
    // Absent before they were recorded (2026-12-01): mine's defaults then.
    out.similarity = params.GetOr<std::string>("similarity", motifmine::defaults::kSimilarity);
    if (problem.empty() && out.similarity != "warped" && out.similarity != "shared") {
      problem = where + ": \"similarity\" is neither warped nor shared";
    }
    out.pause_speed = params.GetOr<double>("pause_speed", motifmine::defaults::kPauseSpeed);
    out.pause_seconds = params.GetOr<double>("pause_seconds", motifmine::defaults::kPauseSeconds);
  }
  {
    Fields files(top.Object("files"), top.Sub("files"), &problem);
    manifest.trellis = ParseFile(files.Object("trellis"), files.Sub("trellis"), &problem);
    manifest.paths = ParseFile(files.Object("paths"), files.Sub("paths"), &problem);
    manifest.motifs = ParseFile(files.Object("motifs"), files.Sub("motifs"), &problem);
    manifest.report = ParseFile(files.Object("report"), files.Sub("report"), &problem);
  }
  {
    Fields build(top.Object("build"), top.Sub("build"), &problem);
    manifest.build.kind = build.Get<std::string>("kind");
    manifest.build.previous_version = build.Get<uint64_t>("previous_version");
    manifest.build.new_takes = build.Get<uint64_t>("new_takes");
    manifest.build.new_frames = build.Get<uint64_t>("new_frames");
    manifest.build.changed_columns = build.Get<uint64_t>("changed_columns");
    manifest.build.copied_blocks = build.Get<uint64_t>("copied_blocks");
    manifest.build.rewritten_blocks = build.Get<uint64_t>("rewritten_blocks");
    manifest.build.seconds = build.Get<double>("seconds");
  }
  if (!problem.empty()) return Status::InvalidArgument(problem);
  if (manifest.version == 0 || manifest.dir != VersionDirName(manifest.version)) {
    return Status::InvalidArgument(name + ": \"dir\" " + manifest.dir + " is not version " +
                                   std::to_string(manifest.version) + "'s folder");
  }
  for (const VersionFile* file : {&manifest.trellis, &manifest.paths, &manifest.motifs}) {
    if (file->path.empty()) return Status::InvalidArgument(name + ": a file path is empty");
  }
  return manifest;
}

Result<ReindexManifest> ReadManifest(const std::string& out_dir) {
  const std::string path = ManifestPath(out_dir);
  MOTIF_ASSIGN_OR_RETURN(std::string text, ReadFileToString(path));
  return ParseManifest(text, path);
}

Status WriteManifest(const std::string& out_dir, const ReindexManifest& manifest,
                     FileSystem* file_system, bool* switched) {
  if (switched) *switched = false;
  const std::string path = ManifestPath(out_dir);
  const std::string temp = TemporaryPathFor(path);
  const std::string text = ManifestText(manifest);
  Status status = [&]() -> Status {
    MOTIF_ASSIGN_OR_RETURN(auto file, file_system->OpenWritable(temp, OpenMode::kCreateExclusive));
    MOTIF_RETURN_IF_ERROR(file->WriteAt(0, text.data(), text.size()));
    MOTIF_RETURN_IF_ERROR(file->Sync());
    MOTIF_RETURN_IF_ERROR(file->Close());
    return file_system->Rename(temp, path);
  }();
  if (!status.ok()) {
    (void)file_system->Remove(temp);  // best effort: the error that matters is `status`
    return status.WithContext(path);
  }
  if (switched) *switched = true;
  status = file_system->SyncParentDir(path);
  return status.ok() ? status : status.WithContext(path);
}

}  // namespace motif
