// End-to-end motif mining checked against known repeats:
//  * a procedural synthetic archive with 10 planted motifs (0.5-5 s, uniform and non-uniform
//    warps of 0.7-1.4x, noise): recall >= 0.9, precision >= 0.8, ARI >= 0.8;
//  * the paper's own check on real data (Meng et al. 2008): one ~3.5 s segment of a real take
//    inserted three times, at different speeds, into a concatenation of 9 other real takes is
//    found three times and grouped into one motif (skipped when the CMU takes are absent).
// Both run MinePipeline, as `motifmine mine` does, with its defaults (the joint-angle eps,
// lambda 0.5 s, B = 5), with the exact search (recall 1, and faster than LSH at this size).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/cluster/motif_clusterer.h"
#include "engine/cluster/motifs_json.h"
#include "engine/evaluation/planted_motif_score.h"
#include "engine/evaluation/truth_score.h"
#include "engine/pipeline/mine_pipeline.h"
#include "engine/synth/motion_synthesizer.h"
#include "engine/synth/segment_insertion.h"
#include "engine/trellis/trellis_builder.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/import/take_importer.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/quaternion_math.h"
#include "formats/paths_file/paths_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"
#include "tests/testing/mocap_data.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

// The motifs of `archive` mined by MinePipeline with the defaults of `motifmine mine` (the exact
// search: recall 1, and faster than LSH at this size), as found instances (clip-relative ranges,
// motif = rank).
std::vector<FoundInstance> MineArchive(const testing::TempDir& dir, const std::string& archive) {
  motifmine::MineOptions options;
  options.out_dir = dir.File("mined");
  options.search = "exact";
  options.threads = 2;
  options.write_report = false;
  Result<MinePipelineResult> run = RunMine(options, {archive});
  EXPECT_TRUE(run.ok()) << run.status().ToString();
  if (!run.ok()) return {};
  std::vector<FoundInstance> found;
  for (const MotifsJsonMotif& motif : run->document.motifs) {
    for (const MotifsJsonInstance& instance : motif.instances) {
      found.push_back({instance.clip, instance.start, instance.end, motif.id});
    }
  }
  return found;
}

TEST(PlantedMotifs, ProceduralArchiveWithTenMotifsIsMinedWithHighRecallPrecisionAndAri) {
  testing::TempDir dir;
  const std::string archive = dir.File("planted.mfs");
  SynthOptions options;  // warps 0.7-1.4x (half non-uniform), noise 1 degree, motifs 0.5-5 s
  options.frames = 40000;
  options.motifs = 10;
  options.instances_min = 3;
  options.instances_max = 4;
  options.seed = 5;
  options.background_variation_degrees = kRecommendedBackgroundVariation;  // as motifmine synth
  auto synthesizer = MotionSynthesizer::Create(options);
  ASSERT_TRUE(synthesizer.ok()) << synthesizer.status().ToString();
  {
    auto writer = FrameFileWriter::Create(archive, (*synthesizer)->skeleton(), options.fps);
    ASSERT_TRUE(writer.ok()) << writer.status().ToString();
    ASSERT_TRUE((*synthesizer)
                    ->Run([&](const ClipFrames& clip) { return (*writer)->AppendClip(clip); })
                    .ok());
    ASSERT_TRUE((*writer)->Commit().ok());
  }
  const std::vector<PlantedInstance>& planted = (*synthesizer)->truth();
  std::set<uint32_t> planted_motifs;
  bool nonuniform = false;
  for (const PlantedInstance& instance : planted) {
    planted_motifs.insert(instance.motif);
    nonuniform = nonuniform || instance.nonuniform;
  }
  ASSERT_EQ(planted_motifs.size(), 10u);
  EXPECT_TRUE(nonuniform);

  const std::vector<FoundInstance> found = MineArchive(dir, archive);
  const PlantedMotifScore score = ScorePlantedMotifs(found, planted);
  SCOPED_TRACE("planted " + std::to_string(score.planted) + ", found " +
               std::to_string(score.found) + " in " + std::to_string(score.found_motifs) +
               " motifs");
  EXPECT_GE(score.recall, 0.9) << score.planted_hit << " of " << score.planted << " planted hit";
  EXPECT_GE(score.precision, 0.8) << score.found_hitting << " of " << score.found
                                  << " found instances hit a planted one";
  EXPECT_GE(score.adjusted_rand_index, 0.8);
}

// ---- The paper's check on real takes --------------------------------------------------------

TEST(PlantedMotifs, RealSegmentInsertedThreeTimesAtDifferentSpeedsIsFoundAsOneMotif) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string bvh = testing::MocapDir() + "/bvh/";
  // The inserted move: 3.5 s of a dance with expressive arms (05_02), as the paper inserted one
  // 434-frame clip. The hosts: 9 other takes of varied content (jumps, punches, dance,
  // basketball, navigation), none of them 05_02.
  const std::string source_name = "05_02";
  const size_t segment_start = 300;
  const size_t segment_frames = 420;
  const std::vector<std::string> host_names = {"01_01", "02_05", "05_04", "05_09", "06_13",
                                               "02_04", "05_06", "09_12", "05_18"};
  auto import = [&](const std::string& name) -> Take {
    auto take = ImportTake({TakeFormat::kBvh, bvh + name + ".bvh", "", ""}, ImportOptions{});
    EXPECT_TRUE(take.ok()) << take.status().ToString();
    return take.ok() ? std::move(*take) : Take{};
  };
  const Take source = import(source_name);
  ASSERT_GE(source.frame_count(), segment_start + segment_frames + 1);
  const double last = static_cast<double>(segment_frames - 1);

  // Three copies: uniformly slower (0.8x speed, 525 frames), uniformly faster (1.25x, 336
  // frames) and non-uniform (mean speed 1, local speed 0.6x to 1.4x, 420 frames).
  struct Copy {
    size_t host;      // index into host_names
    double at_share;  // where in the host, as a share of its length
    Segment segment;
  };
  std::vector<Copy> copies;
  {
    const size_t slow = 525;
    copies.push_back(
        {1, 0.4, WarpSegment(source, segment_start, segment_frames, slow, [&](size_t k) {
           return last * static_cast<double>(k) / static_cast<double>(slow - 1);
         })});
    const size_t fast = 336;
    copies.push_back(
        {2, 0.5, WarpSegment(source, segment_start, segment_frames, fast, [&](size_t k) {
           return last * static_cast<double>(k) / static_cast<double>(fast - 1);
         })});
    const size_t uneven = 420;
    copies.push_back(
        {7, 0.6, WarpSegment(source, segment_start, segment_frames, uneven, [&](size_t k) {
           // x + c sin(2 pi x) / (2 pi): speed 1 + c cos(2 pi x)
           const double x = static_cast<double>(k) / static_cast<double>(uneven - 1);
           return last * (x + 0.4 * std::sin(2 * kPi * x) / (2 * kPi));
         })});
  }

  testing::TempDir dir;
  const std::string archive = dir.File("inserted.mfs");
  std::map<std::string, std::pair<uint64_t, uint64_t>> inserted;  // clip -> [start, end)
  {
    std::unique_ptr<FrameFileWriter> writer;
    for (size_t host_idx = 0; host_idx < host_names.size(); ++host_idx) {
      Take take = import(host_names[host_idx]);
      ASSERT_GT(take.frame_count(), 100u);
      for (const Copy& copy : copies) {
        if (copy.host != host_idx) continue;
        const size_t at =
            static_cast<size_t>(copy.at_share * static_cast<double>(take.frame_count()));
        take = InsertSegment(take, at, copy.segment);
        inserted[take.name] = {at, at + copy.segment.root_positions.size()};
      }
      if (!writer) {
        auto created = FrameFileWriter::Create(archive, take.skeleton, take.fps);
        ASSERT_TRUE(created.ok()) << created.status().ToString();
        writer = std::move(*created);
      }
      ASSERT_TRUE(writer->AppendClip(TakeToClipFrames(take)).ok());
    }
    ASSERT_TRUE(writer->Commit().ok());
  }
  ASSERT_EQ(inserted.size(), 3u);

  const std::vector<FoundInstance> found = MineArchive(dir, archive);
  // For each copy, the motifs with an instance that hits it.
  std::vector<std::set<uint32_t>> motifs_of_copy;
  for (const auto& [clip, range] : inserted) {
    std::set<uint32_t> motifs;
    for (const FoundInstance& instance : found) {
      if (instance.clip == clip &&
          InstancesHit(instance.start, instance.end, range.first, range.second)) {
        motifs.insert(instance.motif);
      }
    }
    EXPECT_FALSE(motifs.empty()) << "the copy in " << clip << " [" << range.first << ", "
                                 << range.second << ") was not found";
    double best_iou = 0;
    for (const FoundInstance& instance : found) {
      if (instance.clip != clip) continue;
      best_iou =
          std::max(best_iou, IntervalIoU(instance.start, instance.end, range.first, range.second));
    }
    std::printf("  the copy in %s [%llu, %llu): best IoU of a found instance %.2f\n", clip.c_str(),
                static_cast<unsigned long long>(range.first),
                static_cast<unsigned long long>(range.second), best_iou);
    motifs_of_copy.push_back(std::move(motifs));
  }
  // One motif holds all three copies.
  std::set<uint32_t> common = motifs_of_copy[0];
  for (const std::set<uint32_t>& motifs : motifs_of_copy) {
    std::set<uint32_t> kept;
    for (uint32_t motif : common) {
      if (motifs.count(motif)) kept.insert(motif);
    }
    common = std::move(kept);
  }
  EXPECT_FALSE(common.empty()) << "the three copies are not in one motif";
}

}  // namespace
}  // namespace motif
