#include "tests/formats/frame_file/frame_file_test_util.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace motif::testing {

std::string Numbered(const std::string& prefix, uint64_t index) {
  std::string name = prefix;
  name += std::to_string(index);
  return name;
}

Skeleton MakeSkeleton(uint32_t joint_count) {
  std::vector<Joint> joints(joint_count);
  for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    Joint& joint = joints[joint_idx];
    joint.name = Numbered("j", joint_idx);
    joint.parent = static_cast<int32_t>(joint_idx) - 1;
    joint.offset = {0.0, joint_idx == 0 ? 0.0 : 10.0 + joint_idx, 0.5 * joint_idx};
    joint.has_end_site = joint_idx + 1 == joint_count;
    if (joint.has_end_site) joint.end_site = {0.0, 5.0, 1.25};
    if (joint_idx == 0) {
      joint.channels = {ChannelType::kXPosition, ChannelType::kYPosition, ChannelType::kZPosition,
                        ChannelType::kZRotation, ChannelType::kYRotation, ChannelType::kXRotation};
    } else {
      joint.channels = {ChannelType::kZRotation, ChannelType::kXRotation, ChannelType::kYRotation};
    }
    joint.weight = joint_idx % 3 == 2 ? 0.0f : 1.0f;
  }
  return Skeleton("custom", std::move(joints));
}

ClipFrames MakeClip(const std::string& name, uint32_t joint_count, uint64_t frame_count,
                    uint32_t seed, double fps) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 1.0);
  const FrameLayout layout{joint_count};
  const size_t stride = layout.stride();

  ClipFrames clip;
  clip.info.name = name;
  clip.info.source_path = "/data/" + name + ".bvh";
  clip.info.frame_count = frame_count;
  clip.info.fps = fps;
  clip.info.source_fps = 2 * fps;
  clip.info.meters_per_unit = 0.0254;
  clip.info.content_hash = 0x9e3779b97f4a7c15ull * (seed + 1);
  clip.info.start_position = {uniform(random), 17.25 + uniform(random), -3.5 * uniform(random)};
  for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
    const float scale = static_cast<float>(1.0 + 0.1 * uniform(random));
    clip.info.joint_offsets.push_back({0.0f, 10.0f * scale, 0.5f * joint_idx * scale});
    clip.info.end_sites.push_back({0.0f, joint_idx + 1 == joint_count ? 5.0f * scale : 0.0f, 0.0f});
  }

  struct JointMotion {
    double axis[3], drift[3], amplitude, frequency, phase;
  };
  std::vector<JointMotion> motions(joint_count);
  for (JointMotion& motion : motions) {
    for (int axis = 0; axis < 3; ++axis) {
      motion.axis[axis] = uniform(random);
      motion.drift[axis] = 0.3 * uniform(random);
    }
    motion.amplitude = 0.2 + 0.8 * std::fabs(uniform(random));
    motion.frequency = 0.3 + 1.5 * std::fabs(uniform(random));
    motion.phase = 3.0 * uniform(random);
  }
  const double heading_rate = 0.5 * uniform(random);
  clip.rows.assign(frame_count * stride, 0.0f);
  for (uint64_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    const double t = static_cast<double>(frame_idx) / fps;
    float* row = &clip.rows[frame_idx * stride];
    for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
      const JointMotion& motion = motions[joint_idx];
      double axis[3];
      for (int component = 0; component < 3; ++component) {
        axis[component] = motion.axis[component] + motion.drift[component] * std::sin(0.4 * t);
      }
      const double norm = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
      const double angle =
          motion.amplitude * std::sin(6.283185307 * motion.frequency * t + motion.phase) +
          0.001 * noise(random);
      // |angle| < pi, so w = cos(angle / 2) > 0: signs are continuous.
      float* q = row + layout.quaternion_offset(joint_idx);
      q[0] = static_cast<float>(std::cos(angle / 2));
      for (int component = 0; component < 3; ++component) {
        q[1 + component] = static_cast<float>(std::sin(angle / 2) * axis[component] / norm);
      }
    }
    row[layout.height_offset()] =
        static_cast<float>(17.0 + 0.8 * std::sin(2.0 * t) + 0.01 * noise(random));
    row[layout.velocity_offset()] = static_cast<float>(3.0 * std::sin(0.7 * t));
    row[layout.velocity_offset() + 1] = static_cast<float>(40.0 + 5.0 * std::cos(1.3 * t));
    row[layout.heading_offset()] = static_cast<float>(heading_rate * t + 0.2 * std::sin(t));
  }
  return clip;
}

void WriteArchive(const std::string& path, const Skeleton& skeleton,
                  const std::vector<ClipFrames>& clips, const FrameFileWriterOptions& options,
                  double fps) {
  auto writer = FrameFileWriter::Create(path, skeleton, fps, options);
  ASSERT_TRUE(writer.ok()) << writer.status().ToString();
  for (const ClipFrames& clip : clips) {
    ASSERT_TRUE((*writer)->AppendClip(clip).ok()) << clip.info.name;
  }
  Status committed = (*writer)->Commit();
  ASSERT_TRUE(committed.ok()) << committed.ToString();
}

void AppendToArchive(const std::string& path, const std::vector<ClipFrames>& clips,
                     const FrameFileWriterOptions& options) {
  auto writer = FrameFileWriter::OpenForAppend(path, options);
  ASSERT_TRUE(writer.ok()) << writer.status().ToString();
  for (const ClipFrames& clip : clips) {
    Status appended = (*writer)->AppendClip(clip);
    ASSERT_TRUE(appended.ok()) << appended.ToString();
  }
  Status committed = (*writer)->Commit();
  ASSERT_TRUE(committed.ok()) << committed.ToString();
}

Result<ArchiveContents> ReadContents(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(auto reader, FrameFileReader::Open(path));
  ArchiveContents contents;
  contents.skeleton = reader->skeleton();
  contents.fps = reader->fps();
  contents.clips = reader->clips();
  MOTIF_RETURN_IF_ERROR(reader->ReadFrames(0, reader->frame_count(), &contents.rows));
  return contents;
}

void ExpectSameClipInfo(const ClipInfo& expected, const ClipInfo& actual) {
  EXPECT_EQ(expected.name, actual.name);
  EXPECT_EQ(expected.source_path, actual.source_path);
  EXPECT_EQ(expected.first_frame, actual.first_frame) << expected.name;
  EXPECT_EQ(expected.frame_count, actual.frame_count) << expected.name;
  EXPECT_EQ(expected.fps, actual.fps);
  EXPECT_EQ(expected.source_fps, actual.source_fps);
  EXPECT_EQ(expected.meters_per_unit, actual.meters_per_unit);
  EXPECT_EQ(expected.content_hash, actual.content_hash);
  EXPECT_EQ(expected.start_position, actual.start_position);
  EXPECT_EQ(expected.joint_offsets, actual.joint_offsets);
  EXPECT_EQ(expected.end_sites, actual.end_sites);
  EXPECT_EQ(expected.source_first_frame, actual.source_first_frame) << expected.name;
  EXPECT_EQ(expected.source_joint_names, actual.source_joint_names) << expected.name;
  EXPECT_EQ(expected.description, actual.description) << expected.name;
}

void ExpectSameSkeleton(const Skeleton& expected, const Skeleton& actual) {
  EXPECT_EQ(expected.family(), actual.family());
  ASSERT_EQ(expected.joint_count(), actual.joint_count());
  for (size_t joint_idx = 0; joint_idx < expected.joint_count(); ++joint_idx) {
    const Joint& a = expected.joint(joint_idx);
    const Joint& b = actual.joint(joint_idx);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.parent, b.parent);
    EXPECT_EQ(a.offset, b.offset);
    EXPECT_EQ(a.has_end_site, b.has_end_site);
    EXPECT_EQ(a.end_site, b.end_site);
    EXPECT_EQ(a.channels, b.channels);
    EXPECT_EQ(a.weight, b.weight);
  }
}

bool SameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

void ExpectSameContents(const ArchiveContents& expected, const ArchiveContents& actual) {
  ExpectSameSkeleton(expected.skeleton, actual.skeleton);
  EXPECT_EQ(expected.fps, actual.fps);
  ASSERT_EQ(expected.clips.size(), actual.clips.size());
  for (size_t clip_idx = 0; clip_idx < expected.clips.size(); ++clip_idx) {
    ExpectSameClipInfo(expected.clips[clip_idx], actual.clips[clip_idx]);
  }
  EXPECT_TRUE(SameBits(expected.rows, actual.rows)) << "decoded rows differ";
}

void ExpectWithinQuantisationBound(const std::vector<float>& written,
                                   const std::vector<float>& decoded, uint32_t joint_count,
                                   const FrameFileWriterOptions& options) {
  const FrameLayout layout{joint_count};
  const size_t stride = layout.stride();
  ASSERT_EQ(written.size(), decoded.size());
  const size_t frame_count = written.size() / stride;
  double worst_angle = 0;
  auto check_scalar = [&](size_t index, double step, const char* what) {
    const double bound = step / 2 * (1 + 1e-9) + std::fabs(written[index]) * 1.2e-7;
    EXPECT_LE(std::fabs(static_cast<double>(written[index]) - decoded[index]), bound)
        << what << " at float " << index;
  };
  for (size_t frame_idx = 0; frame_idx < frame_count; ++frame_idx) {
    const size_t row = frame_idx * stride;
    for (uint32_t joint_idx = 0; joint_idx < joint_count; ++joint_idx) {
      const float* a = &written[row + layout.quaternion_offset(joint_idx)];
      const float* b = &decoded[row + layout.quaternion_offset(joint_idx)];
      double dot = 0, norm_a = 0, norm_b = 0;
      for (int component = 0; component < 4; ++component) {
        dot += static_cast<double>(a[component]) * b[component];
        norm_a += static_cast<double>(a[component]) * a[component];
        norm_b += static_cast<double>(b[component]) * b[component];
        EXPECT_LE(std::fabs(a[component] - b[component]), 2 * options.quaternion_step + 1e-6);
      }
      EXPECT_NEAR(norm_b, 1.0, 1e-6);
      const double cosine = std::min(1.0, std::fabs(dot) / std::sqrt(norm_a * norm_b));
      worst_angle = std::max(worst_angle, 2 * std::acos(cosine));
    }
    check_scalar(row + layout.height_offset(), options.height_step, "height");
    check_scalar(row + layout.velocity_offset(), options.velocity_step, "velocity x");
    check_scalar(row + layout.velocity_offset() + 1, options.velocity_step, "velocity z");
    check_scalar(row + layout.heading_offset(), options.heading_step, "heading");
  }
  EXPECT_LE(worst_angle, 4 * options.quaternion_step);
}

std::vector<std::string> ListDir(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

namespace {

class RecordingFile final : public WritableFile {
 public:
  RecordingFile(RecordingFileSystem* owner, std::unique_ptr<WritableFile> base)
      : owner_(owner), base_(std::move(base)) {}
  Status WriteAt(uint64_t offset, const void* data, size_t size) override {
    owner_->Log("write " + std::to_string(offset) + " " + std::to_string(size));
    return base_->WriteAt(offset, data, size);
  }
  Status Sync() override {
    owner_->Log("fsync");
    return base_->Sync();
  }
  Status Truncate(uint64_t size) override {
    owner_->Log("truncate " + std::to_string(size));
    return base_->Truncate(size);
  }
  Result<uint64_t> Size() override { return base_->Size(); }
  Status Close() override { return base_->Close(); }
  const std::string& path() const override { return base_->path(); }

 private:
  RecordingFileSystem* owner_;
  std::unique_ptr<WritableFile> base_;
};

}  // namespace

Result<std::unique_ptr<WritableFile>> RecordingFileSystem::OpenWritable(const std::string& path,
                                                                        OpenMode mode) {
  Log("open " + path);
  MOTIF_ASSIGN_OR_RETURN(auto file, base_->OpenWritable(path, mode));
  return std::unique_ptr<WritableFile>(new RecordingFile(this, std::move(file)));
}

Status RecordingFileSystem::Rename(const std::string& from, const std::string& to) {
  Log("rename");
  return base_->Rename(from, to);
}

Status RecordingFileSystem::SyncParentDir(const std::string& path) {
  Log("fsync directory");
  return base_->SyncParentDir(path);
}

Status RecordingFileSystem::Remove(const std::string& path) {
  Log("remove");
  return base_->Remove(path);
}

}  // namespace motif::testing
