// The paper's check (Meng et al. 2008) over several sources and seeds: a segment of a real take
// is inserted three times into other real takes (or three times into one take), at speeds drawn
// from 0.8-1.3x (the third copy's speed varying along it, 0.6x-1.4x around its mean), with
// smooth noise of 1 degree on every joint (engine/synth/segment_insertion.h), and the
// archive is mined as `motifmine mine` does with its defaults (exact search). Prints, per copy,
// the best IoU of a found instance, and whether one motif holds all three copies at IoU >= 0.8.
// scripts/check_inserted_copies.sh runs it over 3 sources and 3 seeds
// (docs/design/motif_quality.md).
//
//   inserted_copies_check BVH_DIR SOURCE START SEED [one-take]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "engine/cluster/motif_clusterer.h"
#include "engine/cluster/motifs_json.h"
#include "engine/evaluation/truth_score.h"
#include "engine/pipeline/mine_pipeline.h"
#include "engine/synth/segment_insertion.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/import/take_importer.h"
#include "formats/motion/pose_frames.h"

namespace motif {
namespace {

constexpr size_t kSegmentFrames = 420;
constexpr double kNoiseDegrees = 1.0;  // small noise on every joint of every copy
const std::vector<std::string> kHosts = {"01_01", "02_05", "05_04", "05_09", "06_13",
                                         "02_04", "05_06", "09_12", "05_18"};

struct Found {
  std::string clip;
  uint64_t start = 0;
  uint64_t end = 0;
  uint32_t motif = 0;
};

// The archive mined as `motifmine mine` mines it (the exact search, no report).
Result<std::vector<Found>> Mine(const std::string& dir, const std::string& archive) {
  motifmine::MineOptions options;
  options.out_dir = dir;
  options.search = "exact";
  options.write_report = false;
  MOTIF_ASSIGN_OR_RETURN(const MinePipelineResult run, RunMine(options, {archive}));
  const MotifsDocument& document = run.document;
  std::vector<Found> found;
  for (const MotifsJsonMotif& motif : document.motifs) {
    for (const MotifsJsonInstance& instance : motif.instances) {
      found.push_back({instance.clip, instance.start, instance.end, motif.id});
    }
  }
  return found;
}

// Copy `index` of three: uniform speed for the first two, varying along the third.
Segment MakeCopy(const Take& source, size_t start, int index, std::mt19937_64& random) {
  const double speed = std::uniform_real_distribution<double>(0.8, 1.3)(random);
  const size_t out = static_cast<size_t>(std::lround(kSegmentFrames / speed));
  const double last = static_cast<double>(kSegmentFrames - 1);
  Segment copy = WarpSegment(source, start, kSegmentFrames, out, [&](size_t k) {
    const double x = static_cast<double>(k) / static_cast<double>(out - 1);
    const double wobble =
        index == 2 ? 0.4 * std::sin(2 * std::numbers::pi * x) / (2 * std::numbers::pi) : 0.0;
    return last * (x + wobble);
  });
  AddSmoothNoise(&copy, kNoiseDegrees, 30, random());
  return copy;
}

int Run(const std::string& bvh_dir, const std::string& source_name, size_t start, uint64_t seed,
        bool one_take) {
  auto import = [&](const std::string& name) {
    return ImportTake({TakeFormat::kBvh, bvh_dir + "/" + name + ".bvh", "", ""}, ImportOptions{});
  };
  auto source = import(source_name);
  if (!source.ok() || source->frame_count() < start + kSegmentFrames + 1) {
    std::fprintf(stderr, "source %s: unusable\n", source_name.c_str());
    return 1;
  }
  std::mt19937_64 random(seed);
  std::vector<std::string> hosts;
  for (const std::string& host : kHosts) {
    if (host != source_name) hosts.push_back(host);
  }
  std::shuffle(hosts.begin(), hosts.end(), random);
  // Copy i goes into host copy_host[i] at a share of its length.
  std::vector<size_t> copy_host = {0, 1, 2};
  std::vector<double> shares;
  for (int i = 0; i < 3; ++i) {
    shares.push_back(one_take ? 0.2 + 0.3 * i
                              : std::uniform_real_distribution<double>(0.2, 0.8)(random));
  }
  if (one_take) copy_host = {0, 0, 0};
  std::vector<Segment> copies;
  for (int i = 0; i < 3; ++i) copies.push_back(MakeCopy(*source, start, i, random));

  const std::string dir =
      std::filesystem::temp_directory_path() / ("inserted_copies_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string archive = dir + "/a.mfs";
  std::vector<std::pair<std::string, std::pair<uint64_t, uint64_t>>> inserted;
  {
    std::unique_ptr<FrameFileWriter> writer;
    for (size_t host_idx = 0; host_idx < hosts.size(); ++host_idx) {
      auto take = import(hosts[host_idx]);
      if (!take.ok()) return 1;
      // Later positions first, so earlier ones keep their frame numbers.
      std::vector<int> here;
      for (int i = 0; i < 3; ++i) {
        if (copy_host[i] == host_idx) here.push_back(i);
      }
      std::sort(here.begin(), here.end(), [&](int a, int b) { return shares[a] > shares[b]; });
      std::vector<std::pair<size_t, size_t>> ranges;
      for (int i : here) {
        const size_t at = static_cast<size_t>(shares[i] * static_cast<double>(take->frame_count()));
        *take = InsertSegment(*take, at, copies[i]);
        for (auto& range : ranges) {
          if (range.first < at) continue;
          range.first += copies[i].frame_count();
          range.second += copies[i].frame_count();
        }
        ranges.push_back({at, at + copies[i].frame_count()});
      }
      for (const auto& range : ranges) inserted.push_back({take->name, range});
      if (!writer) {
        auto created = FrameFileWriter::Create(archive, take->skeleton, take->fps);
        if (!created.ok()) return 1;
        writer = std::move(*created);
      }
      if (!writer->AppendClip(TakeToClipFrames(*take)).ok()) return 1;
    }
    if (!writer->Commit().ok()) return 1;
  }
  auto found = Mine(dir, archive);
  std::filesystem::remove_all(dir);
  if (!found.ok()) {
    std::fprintf(stderr, "%s\n", found.status().ToString().c_str());
    return 1;
  }
  std::printf("source %s start %zu seed %llu %s:", source_name.c_str(), start,
              static_cast<unsigned long long>(seed), one_take ? "one take" : "three takes");
  std::map<uint32_t, int> copies_in_motif;  // motif -> copies it covers at IoU >= 0.8
  for (const auto& [clip, range] : inserted) {
    double best = 0;
    std::set<uint32_t> motifs;
    for (const Found& instance : *found) {
      if (instance.clip != clip) continue;
      const double iou = IntervalIoU(instance.start, instance.end, range.first, range.second);
      best = std::max(best, iou);
      if (iou >= 0.8) motifs.insert(instance.motif);
    }
    for (uint32_t motif : motifs) ++copies_in_motif[motif];
    std::printf(" %s [%llu, %llu) IoU %.2f;", clip.c_str(),
                static_cast<unsigned long long>(range.first),
                static_cast<unsigned long long>(range.second), best);
  }
  int grouped = 0;
  for (const auto& [motif, count] : copies_in_motif) grouped = std::max(grouped, count);
  std::printf(" grouped %d/3\n", grouped);
  return 0;
}

}  // namespace
}  // namespace motif

int main(int argc, char** argv) {
  if (argc < 5 || argc > 6) {
    std::fprintf(stderr, "usage: inserted_copies_check BVH_DIR SOURCE START SEED [one-take]\n");
    return 2;
  }
  return motif::Run(argv[1], argv[2], std::stoul(argv[3]), std::stoull(argv[4]),
                    argc == 6 && std::string(argv[5]) == "one-take");
}
