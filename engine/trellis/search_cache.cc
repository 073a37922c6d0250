#include "engine/trellis/search_cache.h"

#include <cstring>

#include <xxhash.h>

#include "common/byte_coding.h"
#include "common/file_util.h"
#include "common/mapped_file.h"

namespace motif {
namespace {

// Byte layout (docs/formats/search_cache.md):
//   [header 72 B + family]  magic, version, sizes, identities, flags, family string
//   [weights f32 x J] [joints u32 x J] [clip starts u64 x C] [features i16 x N x 4J]
//   [per table: keys u32 x N, sort values i16 x N, frames u32 x N, (codes u32 x N)]
//   [thresholds f32 x N]                      when flag bit 1
//   [checksum u64]                            XXH3-64 of every byte before it
constexpr uint8_t kMagic[8] = {0x89, 'M', 'S', 'C', '\r', '\n', 0x1A, '\n'};
constexpr uint16_t kMajor = 1;
constexpr uint16_t kMinor = 0;
constexpr uint64_t kHeaderFixedBytes = 72;
constexpr uint32_t kFlagCodes = 1;
constexpr uint32_t kFlagThresholds = 2;

// Sizes of the sections after the header, for N frames, J joints, C clips, L tables.
uint64_t BodyBytes(uint64_t frames, uint64_t joints, uint64_t clips, uint64_t tables, bool codes,
                   bool thresholds) {
  return joints * 8 + clips * 8 + frames * 4 * joints * 2 +
         tables * frames * (4 + 2 + 4 + (codes ? 4 : 0)) + (thresholds ? frames * 4 : 0);
}

// Appends to a file at increasing offsets while hashing what it writes.
class HashingWriter {
 public:
  explicit HashingWriter(WritableFile* file) : file_(file), state_(XXH3_createState()) {
    XXH3_64bits_reset(state_);
  }
  ~HashingWriter() { XXH3_freeState(state_); }
  Status Write(const void* data, uint64_t size) {
    XXH3_64bits_update(state_, data, size);
    MOTIF_RETURN_IF_ERROR(file_->WriteAt(offset_, data, size));
    offset_ += size;
    return Status::Ok();
  }
  Status Finish() {
    std::string trailer;
    PutU64(&trailer, XXH3_64bits_digest(state_));
    return file_->WriteAt(offset_, trailer.data(), trailer.size());
  }

 private:
  WritableFile* file_;
  XXH3_state_t* state_;
  uint64_t offset_ = 0;
};

template <typename T>
Status WriteArray(HashingWriter* writer, const std::vector<T>& values) {
  return writer->Write(values.data(), values.size() * sizeof(T));
}

// Reads consecutive sections from a mapped file (sizes checked beforehand).
class SectionReader {
 public:
  explicit SectionReader(const uint8_t* data) : data_(data) {}
  template <typename T>
  std::vector<T> Array(uint64_t count) {
    std::vector<T> values(count);
    std::memcpy(values.data(), data_ + offset_, count * sizeof(T));
    offset_ += count * sizeof(T);
    return values;
  }
  const uint8_t* Here() const { return data_ + offset_; }
  void Skip(uint64_t bytes) { offset_ += bytes; }

 private:
  const uint8_t* data_;
  uint64_t offset_ = 0;
};

}  // namespace

Status WriteSearchCache(const std::string& path, const SearchCacheKey& key,
                        const PoseFeatures& features, const LshIndex* index,
                        uint64_t trellis_identity, const std::vector<float>& thresholds,
                        FileSystem* file_system) {
  const uint64_t frames = features.frame_count();
  const bool with_thresholds = trellis_identity != 0 && thresholds.size() == frames;
  const uint32_t tables = index ? index->table_count() : 0;
  const bool codes = index != nullptr && index->position_codes();
  std::string header(kMagic, kMagic + 8);
  PutU16(&header, kMajor);
  PutU16(&header, kMinor);
  PutU32(&header, 0);
  PutU64(&header, frames);
  PutU64(&header, key.archive_identity);
  PutU64(&header, key.weights_hash);
  PutU64(&header, with_thresholds ? trellis_identity : 0);
  PutU32(&header, features.weighted_joint_count());
  PutU32(&header, tables);
  PutU64(&header, features.clip_first_frames().size());
  PutU32(&header, (codes ? kFlagCodes : 0) | (with_thresholds ? kFlagThresholds : 0));
  PutU32(&header, static_cast<uint32_t>(key.family.size()));
  header += key.family;

  const std::string temp = TemporaryPathFor(path);
  Status status = [&]() -> Status {
    MOTIF_ASSIGN_OR_RETURN(auto file, file_system->OpenWritable(temp, OpenMode::kCreateExclusive));
    HashingWriter writer(file.get());
    MOTIF_RETURN_IF_ERROR(writer.Write(header.data(), header.size()));
    MOTIF_RETURN_IF_ERROR(WriteArray(&writer, features.weights()));
    MOTIF_RETURN_IF_ERROR(WriteArray(&writer, features.joints()));
    MOTIF_RETURN_IF_ERROR(WriteArray(&writer, features.clip_first_frames()));
    MOTIF_RETURN_IF_ERROR(writer.Write(features.values(), features.memory_bytes()));
    for (uint32_t table_idx = 0; table_idx < tables; ++table_idx) {
      const LshTableEntries& table = index->table(table_idx);
      MOTIF_RETURN_IF_ERROR(WriteArray(&writer, table.keys));
      MOTIF_RETURN_IF_ERROR(WriteArray(&writer, table.sort_values));
      MOTIF_RETURN_IF_ERROR(WriteArray(&writer, table.frames));
      if (codes) MOTIF_RETURN_IF_ERROR(WriteArray(&writer, table.codes));
    }
    if (with_thresholds) MOTIF_RETURN_IF_ERROR(WriteArray(&writer, thresholds));
    MOTIF_RETURN_IF_ERROR(writer.Finish());
    MOTIF_RETURN_IF_ERROR(file->Close());
    // No fsync: a cache lost or torn by a crash fails its checksum and is built again.
    return file_system->Rename(temp, path);
  }();
  if (!status.ok()) (void)file_system->Remove(temp);  // best effort: `status` is the error
  return status;
}

Result<SearchCache> ReadSearchCache(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(std::unique_ptr<MappedFile> file, MappedFile::Open(path));
  const uint8_t* data = file->data();
  const uint64_t size = file->size();
  auto corrupt = [&](const std::string& what) {
    return Status::Corruption(path + ": search cache " + what);
  };
  if (size < kHeaderFixedBytes + 8 || std::memcmp(data, kMagic, 8) != 0) {
    return corrupt("has no header (bad magic or too short)");
  }
  if (LoadU16(data + 8) != kMajor) return corrupt("of another major version");
  const uint64_t frames = LoadU64(data + 16);
  SearchCache cache;
  cache.key.archive_identity = LoadU64(data + 24);
  cache.key.weights_hash = LoadU64(data + 32);
  cache.trellis_identity = LoadU64(data + 40);
  const uint32_t joints = LoadU32(data + 48);
  const uint32_t tables = LoadU32(data + 52);
  const uint64_t clips = LoadU64(data + 56);
  const uint32_t flags = LoadU32(data + 64);
  const uint32_t family_bytes = LoadU32(data + 68);
  if (LoadU32(data + 12) != 0 || (flags & ~(kFlagCodes | kFlagThresholds)) != 0) {
    return corrupt("has a reserved field or flag set");
  }
  const bool codes = (flags & kFlagCodes) != 0;
  const bool thresholds = (flags & kFlagThresholds) != 0;
  if (frames >= (uint64_t{1} << 32) || joints == 0 || joints > 1024 || tables > 64 || clips == 0 ||
      clips > frames + 1 || family_bytes > (1u << 16)) {
    return corrupt("has impossible sizes");
  }
  const uint64_t header_bytes = kHeaderFixedBytes + family_bytes;
  if (size != header_bytes + BodyBytes(frames, joints, clips, tables, codes, thresholds) + 8) {
    return corrupt("of " + std::to_string(size) + " bytes does not hold what its header says");
  }
  if (LoadU64(data + size - 8) != Checksum64(data, size - 8)) return corrupt("checksum mismatch");
  cache.key.family.assign(reinterpret_cast<const char*>(data) + kHeaderFixedBytes, family_bytes);
  SectionReader sections(data + header_bytes);
  std::vector<float> weights = sections.Array<float>(joints);
  std::vector<uint32_t> joint_ids = sections.Array<uint32_t>(joints);
  std::vector<uint64_t> clip_starts = sections.Array<uint64_t>(clips);
  Result<PoseFeatures> features = PoseFeatures::FromParts(
      frames, std::move(weights), std::move(joint_ids), std::move(clip_starts),
      reinterpret_cast<const int16_t*>(sections.Here()));  // copied bytewise
  if (!features.ok()) return corrupt(features.status().message());
  cache.features = std::move(features.value());
  sections.Skip(frames * 4 * joints * sizeof(int16_t));
  for (uint32_t table_idx = 0; table_idx < tables; ++table_idx) {
    LshTableEntries table;
    table.keys = sections.Array<uint32_t>(frames);
    table.sort_values = sections.Array<int16_t>(frames);
    table.frames = sections.Array<uint32_t>(frames);
    if (codes) table.codes = sections.Array<uint32_t>(frames);
    cache.tables.push_back(std::move(table));
  }
  cache.position_codes = codes;
  if (thresholds) cache.thresholds = sections.Array<float>(frames);
  if (!thresholds) cache.trellis_identity = 0;
  return cache;
}

}  // namespace motif
