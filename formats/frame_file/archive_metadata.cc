#include "formats/frame_file/archive_metadata.h"

#include <cmath>
#include <unordered_set>

namespace motif::frame_file {
namespace {

constexpr size_t kSectionHeaderBytes = 16;
constexpr uint8_t kChannelTypeCount = 6;
// The smallest records, used to bound counts before allocating.
constexpr size_t kMinJointRecordBytes = 4 + 4 + 4 + 24 + 1 + 24 + 4 + 1;
constexpr size_t kMinClipRecordBytes = 4 + 4 + 4 + 8 * 6 + 24 + 4;

uint32_t ComponentsOf(ColumnKind kind) {
  switch (kind) {
    case ColumnKind::kJointRotation:
      return 4;
    case ColumnKind::kRootHeight:
      return 1;
    case ColumnKind::kRootVelocity:
      return 2;
    case ColumnKind::kHeading:
      return 1;
  }
  return 0;
}

// Appends a section: tag u32 | reserved u32 | payload_bytes u64 | payload.
void PutSection(std::string* out, SectionTag tag, const std::string& payload) {
  PutU32(out, static_cast<uint32_t>(tag));
  PutU32(out, 0);
  PutU64(out, payload.size());
  out->append(payload);
}

// Appends record_bytes u32 | record.
void PutRecord(std::string* out, const std::string& record) {
  PutU32(out, static_cast<uint32_t>(record.size()));
  out->append(record);
}

// Column table entry, 24 bytes:
//   0 kind u8 | 1 component_count u8 | 2 quantization u8 | 3 delta_order u8 | 4 zigzag u8
//   5 shuffle u8 | 6 compression u8 | 7 normalize u8 | 8 row_offset u32 | 12 joint_idx u32
//   16 step f64
void EncodeColumn(const ColumnSpec& column, std::string* out) {
  PutU8(out, static_cast<uint8_t>(column.kind));
  PutU8(out, column.component_count);
  PutU8(out, static_cast<uint8_t>(column.encoding.quantization));
  PutU8(out, column.encoding.delta_order);
  PutU8(out, column.encoding.zigzag ? 1 : 0);
  PutU8(out, column.encoding.shuffle ? 1 : 0);
  PutU8(out, static_cast<uint8_t>(column.encoding.compression));
  PutU8(out, column.encoding.normalize ? 1 : 0);
  PutU32(out, column.row_offset);
  PutU32(out, column.joint_idx);
  PutF64(out, column.encoding.step);
}

// Joint record (after its record_bytes u32):
//   name str | parent i32 | offset f64 x3 | has_end_site u8 | end_site f64 x3 | weight f32
//   channel_count u8 | channels u8 x channel_count
void EncodeJoint(const Joint& joint, std::string* out) {
  std::string record;
  PutString(&record, joint.name);
  PutU32(&record, static_cast<uint32_t>(joint.parent));
  for (double value : joint.offset) PutF64(&record, value);
  PutU8(&record, joint.has_end_site ? 1 : 0);
  for (double value : joint.end_site) PutF64(&record, value);
  PutF32(&record, joint.weight);
  PutU8(&record, static_cast<uint8_t>(joint.channels.size()));
  for (ChannelType channel : joint.channels) PutU8(&record, static_cast<uint8_t>(channel));
  PutRecord(out, record);
}

// Clip record (after its record_bytes u32):
//   name str | source_path str | first_frame u64 | frame_count u64 | fps f64 | source_fps f64
//   meters_per_unit f64 | content_hash u64 | start_position f64 x3 | joint_count u32
//   joint_offsets f32 x3 x joint_count | end_sites f32 x3 x joint_count
//   [source_first_frame u64 | name_count u32 | source_joint_names str x name_count
//    | description str]
// The bracketed source fields are appended only when a clip has one of them (not 0, names, a
// description), so the records of clips without them stay as 1.0 wrote them.
void EncodeClip(const ClipInfo& clip, std::string* out) {
  std::string record;
  PutString(&record, clip.name);
  PutString(&record, clip.source_path);
  PutU64(&record, clip.first_frame);
  PutU64(&record, clip.frame_count);
  PutF64(&record, clip.fps);
  PutF64(&record, clip.source_fps);
  PutF64(&record, clip.meters_per_unit);
  PutU64(&record, clip.content_hash);
  for (double value : clip.start_position) PutF64(&record, value);
  PutU32(&record, static_cast<uint32_t>(clip.joint_offsets.size()));
  for (const auto& offset : clip.joint_offsets) {
    for (float value : offset) PutF32(&record, value);
  }
  for (const auto& end_site : clip.end_sites) {
    for (float value : end_site) PutF32(&record, value);
  }
  if (clip.source_first_frame != 0 || !clip.source_joint_names.empty() ||
      !clip.description.empty()) {
    PutU64(&record, clip.source_first_frame);
    PutU32(&record, static_cast<uint32_t>(clip.source_joint_names.size()));
    for (const std::string& name : clip.source_joint_names) PutString(&record, name);
    PutString(&record, clip.description);
  }
  PutRecord(out, record);
}

// Decoding: every failure is Corruption("metadata at offset 0x..: <section>: <problem>").
class SectionDecoder {
 public:
  SectionDecoder(const char* section, uint64_t payload_offset, const uint8_t* payload, size_t size)
      : section_(section), payload_offset_(payload_offset), reader_(payload, size) {}

  ByteReader* reader() { return &reader_; }
  Status Error(const std::string& problem) const {
    return Status::Corruption("metadata " + std::string(section_) + " section at offset " +
                              Hex(payload_offset_ + reader_.position()) + ": " + problem);
  }
  Status Truncated(const std::string& what) const { return Error(what + " runs past the section"); }

  // Reads record_bytes u32 and returns a decoder over the record.
  Status Record(const char* what, SectionDecoder* record) {
    uint32_t record_bytes = 0;
    const uint8_t* bytes = nullptr;
    if (!reader_.GetU32(&record_bytes)) return Truncated(what);
    const uint64_t record_offset = payload_offset_ + reader_.position();
    if (!reader_.GetBytes(record_bytes, &bytes)) return Truncated(what);
    *record = SectionDecoder(section_, record_offset, bytes, record_bytes);
    return Status::Ok();
  }

 private:
  const char* section_;
  uint64_t payload_offset_;
  ByteReader reader_;
};

Status DecodeArchive(SectionDecoder* section, ArchiveMetadata* metadata) {
  ByteReader* reader = section->reader();
  if (!reader->GetF64(&metadata->fps) || !reader->GetU64(&metadata->frame_count) ||
      !reader->GetU32(&metadata->joint_count) || !reader->GetU32(&metadata->block_frames)) {
    return section->Truncated("archive fields");
  }
  if (!std::isfinite(metadata->fps) || !(metadata->fps > 0)) {
    return section->Error("fps " + std::to_string(metadata->fps) + " is not finite and > 0");
  }
  if (metadata->joint_count == 0 || metadata->joint_count > kMaxJoints) {
    return section->Error("joint count " + std::to_string(metadata->joint_count) + " outside [1, " +
                          std::to_string(kMaxJoints) + "]");
  }
  if (metadata->block_frames == 0 || metadata->block_frames > kMaxBlockFrames) {
    return section->Error("block size " + std::to_string(metadata->block_frames) +
                          " frames outside [1, " + std::to_string(kMaxBlockFrames) + "]");
  }
  return Status::Ok();
}

Status DecodeSkeleton(SectionDecoder* section, ArchiveMetadata* metadata) {
  ByteReader* reader = section->reader();
  std::string family;
  uint32_t joint_count = 0;
  if (!reader->GetString(&family)) return section->Truncated("family");
  if (!reader->GetU32(&joint_count)) return section->Truncated("joint count");
  if (joint_count != metadata->joint_count) {
    return section->Error("has " + std::to_string(joint_count) + " joints, the archive " +
                          std::to_string(metadata->joint_count));
  }
  if (reader->remaining() / kMinJointRecordBytes < joint_count) {
    return section->Truncated("joint table");
  }
  std::vector<Joint> joints(joint_count);
  for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    SectionDecoder record("", 0, nullptr, 0);
    MOTIF_RETURN_IF_ERROR(section->Record("joint record", &record));
    ByteReader* fields = record.reader();
    Joint& joint = joints[joint_idx];
    uint8_t has_end_site = 0, channel_count = 0;
    bool ok = fields->GetString(&joint.name) && fields->GetI32(&joint.parent);
    for (double& value : joint.offset) ok = ok && fields->GetF64(&value);
    ok = ok && fields->GetU8(&has_end_site);
    for (double& value : joint.end_site) ok = ok && fields->GetF64(&value);
    ok = ok && fields->GetF32(&joint.weight) && fields->GetU8(&channel_count);
    if (!ok) return record.Truncated("joint " + std::to_string(joint_idx));
    if (has_end_site > 1) return record.Error("has_end_site is neither 0 nor 1");
    joint.has_end_site = has_end_site == 1;
    for (uint8_t channel_idx = 0; channel_idx < channel_count; ++channel_idx) {
      uint8_t channel = 0;
      if (!fields->GetU8(&channel)) return record.Truncated("channel list");
      if (channel >= kChannelTypeCount) {
        return record.Error("unknown channel type " + std::to_string(channel));
      }
      joint.channels.push_back(static_cast<ChannelType>(channel));
    }
  }
  metadata->skeleton = Skeleton(std::move(family), std::move(joints));
  Status valid = metadata->skeleton.Validate();
  if (!valid.ok()) return section->Error(valid.message());
  return Status::Ok();
}

Status DecodeColumns(SectionDecoder* section, ArchiveMetadata* metadata) {
  ByteReader* reader = section->reader();
  uint32_t column_count = 0, entry_bytes = 0;
  if (!reader->GetU32(&column_count) || !reader->GetU32(&entry_bytes)) {
    return section->Truncated("column table header");
  }
  if (entry_bytes < kColumnEntryBytes) {
    return section->Error("column entries of " + std::to_string(entry_bytes) + " bytes, at least " +
                          std::to_string(kColumnEntryBytes) + " needed");
  }
  const uint64_t stride = metadata->layout().stride();
  if (column_count > stride || reader->remaining() / entry_bytes < column_count) {
    return section->Error(std::to_string(column_count) + " columns do not fit");
  }
  metadata->columns.assign(column_count, ColumnSpec());
  for (uint32_t column_idx = 0; column_idx < column_count; ++column_idx) {
    ColumnSpec& column = metadata->columns[column_idx];
    const size_t start = reader->position();
    uint8_t kind = 0, quantization = 0, zigzag = 0, shuffle = 0, compression = 0, normalize = 0;
    reader->GetU8(&kind);
    reader->GetU8(&column.component_count);
    reader->GetU8(&quantization);
    reader->GetU8(&column.encoding.delta_order);
    reader->GetU8(&zigzag);
    reader->GetU8(&shuffle);
    reader->GetU8(&compression);
    reader->GetU8(&normalize);
    reader->GetU32(&column.row_offset);
    reader->GetU32(&column.joint_idx);
    reader->GetF64(&column.encoding.step);
    reader->Skip(entry_bytes - (reader->position() - start));
    if (kind > static_cast<uint8_t>(ColumnKind::kHeading)) {
      return section->Error("column " + std::to_string(column_idx) + ": unknown kind " +
                            std::to_string(kind));
    }
    if (zigzag > 1 || shuffle > 1 || normalize > 1) {
      return section->Error("column " + std::to_string(column_idx) + ": a flag is neither 0 nor 1");
    }
    column.kind = static_cast<ColumnKind>(kind);
    column.encoding.quantization = static_cast<Quantization>(quantization);
    column.encoding.zigzag = zigzag == 1;
    column.encoding.shuffle = shuffle == 1;
    column.encoding.compression = static_cast<Compression>(compression);
    column.encoding.normalize = normalize == 1;
  }
  Status valid = ValidateColumns(metadata->columns, metadata->joint_count);
  if (!valid.ok()) return section->Error(valid.message());
  return Status::Ok();
}

// The optional source fields after a clip's end sites (EncodeClip): absent in older records.
Status DecodeClipSource(SectionDecoder* record, const std::string& what, uint32_t joint_count,
                        ClipInfo* clip) {
  ByteReader* fields = record->reader();
  if (fields->remaining() == 0) return Status::Ok();
  uint32_t name_count = 0;
  if (!fields->GetU64(&clip->source_first_frame) || !fields->GetU32(&name_count)) {
    return record->Truncated(what + " source fields");
  }
  if (name_count != 0 && name_count != joint_count) {
    return record->Error(what + " has " + std::to_string(name_count) +
                         " source joint names, the archive " + std::to_string(joint_count) +
                         " joints");
  }
  if (fields->remaining() / 4 < name_count) return record->Truncated(what + " source joint names");
  clip->source_joint_names.resize(name_count);
  for (std::string& name : clip->source_joint_names) {
    if (!fields->GetString(&name)) return record->Truncated(what + " source joint names");
    if (name.empty()) return record->Error(what + " has an empty source joint name");
  }
  if (!fields->GetString(&clip->description)) return record->Truncated(what + " description");
  return Status::Ok();
}

Status DecodeClips(SectionDecoder* section, ArchiveMetadata* metadata) {
  ByteReader* reader = section->reader();
  uint64_t clip_count = 0;
  if (!reader->GetU64(&clip_count)) return section->Truncated("clip count");
  if (reader->remaining() / kMinClipRecordBytes < clip_count) {
    return section->Error(std::to_string(clip_count) + " clips do not fit");
  }
  metadata->clips.assign(clip_count, ClipInfo());
  std::unordered_set<std::string> names;
  uint64_t next_frame = 0;
  for (uint64_t clip_idx = 0; clip_idx < clip_count; ++clip_idx) {
    SectionDecoder record("", 0, nullptr, 0);
    MOTIF_RETURN_IF_ERROR(section->Record("clip record", &record));
    ByteReader* fields = record.reader();
    ClipInfo& clip = metadata->clips[clip_idx];
    uint32_t joint_count = 0;
    bool ok = fields->GetString(&clip.name) && fields->GetString(&clip.source_path) &&
              fields->GetU64(&clip.first_frame) && fields->GetU64(&clip.frame_count) &&
              fields->GetF64(&clip.fps) && fields->GetF64(&clip.source_fps) &&
              fields->GetF64(&clip.meters_per_unit) && fields->GetU64(&clip.content_hash);
    for (double& value : clip.start_position) ok = ok && fields->GetF64(&value);
    ok = ok && fields->GetU32(&joint_count);
    const std::string what = "clip " + std::to_string(clip_idx);
    if (!ok) return record.Truncated(what);
    if (joint_count != metadata->joint_count) {
      return record.Error(what + " has " + std::to_string(joint_count) +
                          " joint offsets, the archive " + std::to_string(metadata->joint_count) +
                          " joints");
    }
    if (fields->remaining() / 24 < joint_count) return record.Truncated(what + " joint offsets");
    clip.joint_offsets.resize(joint_count);
    clip.end_sites.resize(joint_count);
    for (auto& offset : clip.joint_offsets) {
      for (float& value : offset) fields->GetF32(&value);
    }
    for (auto& end_site : clip.end_sites) {
      for (float& value : end_site) fields->GetF32(&value);
    }
    MOTIF_RETURN_IF_ERROR(DecodeClipSource(&record, what, joint_count, &clip));
    if (clip.name.empty()) return record.Error(what + " has an empty name");
    if (!names.insert(clip.name).second) {
      return record.Error(what + ": name \"" + clip.name + "\" appears twice");
    }
    if (clip.first_frame != next_frame || clip.frame_count == 0 ||
        clip.frame_count > metadata->frame_count - next_frame) {
      return record.Error(what + " (\"" + clip.name + "\") covers frames [" +
                          std::to_string(clip.first_frame) + ", +" +
                          std::to_string(clip.frame_count) + "), expected to start at " +
                          std::to_string(next_frame) + " within " +
                          std::to_string(metadata->frame_count) + " frames");
    }
    next_frame += clip.frame_count;
  }
  if (next_frame != metadata->frame_count) {
    return section->Error("clips cover " + std::to_string(next_frame) + " frames, the archive " +
                          std::to_string(metadata->frame_count));
  }
  return Status::Ok();
}

Status DecodeBlocks(SectionDecoder* section, uint64_t metadata_offset, ArchiveMetadata* metadata) {
  ByteReader* reader = section->reader();
  uint64_t block_count = 0;
  uint32_t entry_bytes = 0, reserved = 0;
  if (!reader->GetU64(&block_count) || !reader->GetU32(&entry_bytes) ||
      !reader->GetU32(&reserved)) {
    return section->Truncated("block index header");
  }
  if (reserved != 0) return section->Error("reserved field is not zero");
  if (entry_bytes < kBlockEntryBytes) {
    return section->Error("block entries of " + std::to_string(entry_bytes) + " bytes, at least " +
                          std::to_string(kBlockEntryBytes) + " needed");
  }
  if (reader->remaining() / entry_bytes < block_count) {
    return section->Error(std::to_string(block_count) + " blocks do not fit");
  }
  metadata->blocks.assign(block_count, BlockHandle());
  const uint64_t stride = metadata->layout().stride();
  const uint64_t min_block_bytes = kBlockHeaderBytes + kChunkEntryBytes * metadata->columns.size();
  uint64_t next_frame = 0;
  uint64_t previous_end = kHeaderBytes;
  for (uint64_t block_idx = 0; block_idx < block_count; ++block_idx) {
    const size_t start = reader->position();
    BlockHandle& block = metadata->blocks[block_idx];
    const std::string what = "block " + std::to_string(block_idx);
    Status decoded = BlockHandle::DecodeFrom(reader, &block);
    if (!decoded.ok()) return section->Error(what + ": " + decoded.message());
    reader->Skip(entry_bytes - (reader->position() - start));
    if (block.first_frame != next_frame || block.frame_count == 0 ||
        block.frame_count > kMaxBlockFrames ||
        block.frame_count > metadata->frame_count - next_frame ||
        block.frame_count * stride * 4 > kMaxBlockRawBytes) {
      return section->Error(what + " holds frames [" + std::to_string(block.first_frame) + ", +" +
                            std::to_string(block.frame_count) + "), expected to start at " +
                            std::to_string(next_frame) + " within " +
                            std::to_string(metadata->frame_count) + " frames");
    }
    if (block.offset < previous_end || block.bytes < min_block_bytes ||
        block.bytes > metadata_offset || block.offset > metadata_offset - block.bytes) {
      return section->Error(what + " at offset " + Hex(block.offset) + " (" +
                            std::to_string(block.bytes) +
                            " bytes) overlaps another block or lies outside [" + Hex(kHeaderBytes) +
                            ", " + Hex(metadata_offset) + ")");
    }
    next_frame += block.frame_count;
    previous_end = block.offset + block.bytes;
  }
  if (next_frame != metadata->frame_count) {
    return section->Error("blocks cover " + std::to_string(next_frame) + " frames, the archive " +
                          std::to_string(metadata->frame_count));
  }
  return Status::Ok();
}

}  // namespace

std::vector<ColumnSpec> DefaultColumns(uint32_t joint_count, const ColumnDefaults& defaults) {
  const FrameLayout layout{joint_count};
  // Measured on the CMU BVH takes at 120 fps (docs/formats/frame_file.md, "Choice of the
  // default encoding"): linear prediction (delta order 2) wins on rotations, height and heading;
  // the root velocity, itself a noisy difference of positions, compresses best with order 1.
  auto encoding = [&](double step, bool normalize, uint8_t delta_order) {
    ColumnEncoding result;
    if (defaults.lossless) {
      result.quantization = Quantization::kNone;
      result.step = 0;
      result.delta_order = 1;
    } else {
      result.step = step;
      result.normalize = normalize;
      result.delta_order = delta_order;
    }
    return result;
  };
  std::vector<ColumnSpec> columns;
  for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    columns.push_back({ColumnKind::kJointRotation, 4,
                       static_cast<uint32_t>(layout.quaternion_offset(joint_idx)), joint_idx,
                       encoding(defaults.quaternion_step, true, 2)});
  }
  columns.push_back({ColumnKind::kRootHeight, 1, static_cast<uint32_t>(layout.height_offset()),
                     kNoJoint, encoding(defaults.height_step, false, 2)});
  columns.push_back({ColumnKind::kRootVelocity, 2, static_cast<uint32_t>(layout.velocity_offset()),
                     kNoJoint, encoding(defaults.velocity_step, false, 1)});
  columns.push_back({ColumnKind::kHeading, 1, static_cast<uint32_t>(layout.heading_offset()),
                     kNoJoint, encoding(defaults.heading_step, false, 2)});
  return columns;
}

Status ValidateColumns(const std::vector<ColumnSpec>& columns, uint32_t joint_count) {
  const size_t stride = FrameLayout{joint_count}.stride();
  std::vector<bool> covered(stride, false);
  for (size_t column_idx = 0; column_idx < columns.size(); ++column_idx) {
    const ColumnSpec& column = columns[column_idx];
    const std::string what = "column " + std::to_string(column_idx);
    if (column.component_count != ComponentsOf(column.kind)) {
      return Status::InvalidArgument(what + ": " + std::to_string(column.component_count) +
                                     " components for kind " +
                                     std::to_string(static_cast<int>(column.kind)));
    }
    const bool is_joint = column.kind == ColumnKind::kJointRotation;
    if (is_joint ? column.joint_idx >= joint_count : column.joint_idx != kNoJoint) {
      return Status::InvalidArgument(what + ": joint index " + std::to_string(column.joint_idx) +
                                     " does not fit its kind");
    }
    Status valid = ValidateEncoding(column.encoding, column.component_count);
    if (!valid.ok()) return valid.WithContext(what);
    if (column.row_offset > stride || column.component_count > stride - column.row_offset) {
      return Status::InvalidArgument(what + " lies outside the " + std::to_string(stride) +
                                     "-float row");
    }
    for (uint32_t component = 0; component < column.component_count; ++component) {
      if (covered[column.row_offset + component]) {
        return Status::InvalidArgument(what + " overlaps another column");
      }
      covered[column.row_offset + component] = true;
    }
  }
  for (size_t float_idx = 0; float_idx < stride; ++float_idx) {
    if (!covered[float_idx]) {
      return Status::InvalidArgument("no column holds float " + std::to_string(float_idx) +
                                     " of the row");
    }
  }
  return Status::Ok();
}

void ArchiveMetadata::EncodeTo(std::string* out) const {
  std::string payload;
  PutF64(&payload, fps);
  PutU64(&payload, frame_count);
  PutU32(&payload, joint_count);
  PutU32(&payload, block_frames);
  PutSection(out, SectionTag::kArchive, payload);

  payload.clear();
  PutString(&payload, skeleton.family());
  PutU32(&payload, static_cast<uint32_t>(skeleton.joint_count()));
  for (const Joint& joint : skeleton.joints()) EncodeJoint(joint, &payload);
  PutSection(out, SectionTag::kSkeleton, payload);

  payload.clear();
  PutU32(&payload, static_cast<uint32_t>(columns.size()));
  PutU32(&payload, static_cast<uint32_t>(kColumnEntryBytes));
  for (const ColumnSpec& column : columns) EncodeColumn(column, &payload);
  PutSection(out, SectionTag::kColumns, payload);

  payload.clear();
  PutU64(&payload, clips.size());
  for (const ClipInfo& clip : clips) EncodeClip(clip, &payload);
  PutSection(out, SectionTag::kClips, payload);

  payload.clear();
  PutU64(&payload, blocks.size());
  PutU32(&payload, static_cast<uint32_t>(kBlockEntryBytes));
  PutU32(&payload, 0);
  for (const BlockHandle& block : blocks) block.EncodeTo(&payload);
  PutSection(out, SectionTag::kBlocks, payload);
}

Status ArchiveMetadata::DecodeFrom(const uint8_t* data, size_t size, uint64_t file_offset,
                                   ArchiveMetadata* metadata) {
  *metadata = ArchiveMetadata();
  ByteReader reader(data, size);
  uint32_t previous_tag = 0;
  uint32_t next_required = static_cast<uint32_t>(SectionTag::kArchive);
  while (reader.remaining() > 0) {
    const uint64_t section_offset = file_offset + reader.position();
    uint32_t tag = 0, reserved = 0;
    uint64_t payload_bytes = 0;
    const uint8_t* payload = nullptr;
    if (!reader.GetU32(&tag) || !reader.GetU32(&reserved) || !reader.GetU64(&payload_bytes)) {
      return Status::Corruption("metadata section header at offset " + Hex(section_offset) +
                                " is truncated");
    }
    if (reserved != 0) {
      return Status::Corruption("metadata section at offset " + Hex(section_offset) +
                                ": reserved field is not zero");
    }
    if (tag <= previous_tag) {
      return Status::Corruption("metadata section at offset " + Hex(section_offset) + ": tag " +
                                std::to_string(tag) + " out of order");
    }
    if (payload_bytes > reader.remaining() || !reader.GetBytes(payload_bytes, &payload)) {
      return Status::Corruption("metadata section at offset " + Hex(section_offset) +
                                ": payload of " + std::to_string(payload_bytes) +
                                " bytes runs past the metadata");
    }
    previous_tag = tag;
    const uint64_t payload_offset = section_offset + kSectionHeaderBytes;
    if (tag > static_cast<uint32_t>(SectionTag::kBlocks)) continue;  // a later minor's section
    if (tag != next_required) {
      return Status::Corruption("metadata section " + std::to_string(next_required) +
                                " is missing (found " + std::to_string(tag) + " at offset " +
                                Hex(section_offset) + ")");
    }
    ++next_required;
    switch (static_cast<SectionTag>(tag)) {
      case SectionTag::kArchive: {
        SectionDecoder section("ARCHIVE", payload_offset, payload, payload_bytes);
        MOTIF_RETURN_IF_ERROR(DecodeArchive(&section, metadata));
        break;
      }
      case SectionTag::kSkeleton: {
        SectionDecoder section("SKELETON", payload_offset, payload, payload_bytes);
        MOTIF_RETURN_IF_ERROR(DecodeSkeleton(&section, metadata));
        break;
      }
      case SectionTag::kColumns: {
        SectionDecoder section("COLUMNS", payload_offset, payload, payload_bytes);
        MOTIF_RETURN_IF_ERROR(DecodeColumns(&section, metadata));
        break;
      }
      case SectionTag::kClips: {
        SectionDecoder section("CLIPS", payload_offset, payload, payload_bytes);
        MOTIF_RETURN_IF_ERROR(DecodeClips(&section, metadata));
        break;
      }
      case SectionTag::kBlocks: {
        SectionDecoder section("BLOCKS", payload_offset, payload, payload_bytes);
        MOTIF_RETURN_IF_ERROR(DecodeBlocks(&section, file_offset, metadata));
        break;
      }
    }
  }
  if (next_required <= static_cast<uint32_t>(SectionTag::kBlocks)) {
    return Status::Corruption("metadata at offset " + Hex(file_offset) + ": section " +
                              std::to_string(next_required) + " is missing");
  }
  return Status::Ok();
}

}  // namespace motif::frame_file
