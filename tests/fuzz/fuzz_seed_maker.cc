// fuzz_seed_maker: writes seed corpora for the fuzz targets (docs/reliability.md, "Fuzzing"):
// small valid inputs of every format, made from the repository's fixtures (tests/data) and,
// with --mocap, from the real CMU takes (../shared/data/mocap), one folder per target:
//
//   fuzz_seed_maker OUT_DIR [--mocap DIR]
//     OUT_DIR/bvh_parser/ asf_parser/ amc_parser/ frame_file_reader/ trellis_file_reader/
//             paths_file_reader/
//
// Without --mocap every seed is a few hundred bytes to a few KB (tests/data/fuzz/<target>/
// holds a selection of them); with it, truncated real BVH takes (hierarchy and a few frames),
// the real ASF skeletons and archives of real motion are added, for the fuzzing runs' corpora
// (kept outside the repository). Deterministic: the same inputs give the same seeds.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "common/status.h"
#include "formats/frame_file/frame_file_writer.h"
#include "formats/import/bvh_parser.h"
#include "formats/motion/canonical_skeleton.h"
#include "formats/motion/pose_frames.h"
#include "formats/motion/resample.h"
#include "formats/paths_file/paths_file_writer.h"
#include "formats/trellis_file/trellis_file_writer.h"

namespace motif {
namespace {

namespace fs = std::filesystem;

const std::string kSourceDir = MOTIF_SOURCE_DIR;

[[noreturn]] void Die(const std::string& message) {
  std::fprintf(stderr, "fuzz_seed_maker: %s\n", message.c_str());
  std::exit(1);
}

void Check(const Status& status, const std::string& what) {
  if (!status.ok()) Die(what + ": " + status.ToString());
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) Die("cannot read " + path.string());
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void WriteSeed(const fs::path& dir, const std::string& name, const std::string& bytes) {
  fs::create_directories(dir);
  std::ofstream out(dir / name, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) Die("cannot write " + (dir / name).string());
}

std::string WithCrLf(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\n') out.push_back('\r');
    out.push_back(c);
  }
  return out;
}

// The hierarchy of a BVH text and its first `frames` frame lines, with "Frames:" adjusted.
std::string TruncatedBvh(const std::string& text, int frames) {
  std::istringstream in(text);
  std::string line;
  std::string out;
  bool in_motion = false;
  int frame_lines = -1;  // counts after "Frame Time:"
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("MOTION", 0) == 0) in_motion = true;
    if (in_motion && line.rfind("Frames:", 0) == 0) {
      out += "Frames: " + std::to_string(frames) + "\n";
      continue;
    }
    if (in_motion && line.rfind("Frame Time:", 0) == 0) {
      out += line + "\n";
      frame_lines = 0;
      continue;
    }
    if (frame_lines >= 0) {
      if (frame_lines == frames) break;
      ++frame_lines;
    }
    out += line + "\n";
  }
  return out;
}

// A take from BVH text as the importer makes it (canonical skeleton), at `fps`.
Take TakeFromBvh(const std::string& text, const std::string& name, double fps) {
  Result<Take> take = ParseBvh(text, name + ".bvh");
  Check(take.status(), "parsing " + name);
  take->name = name;
  CanonicalizeSkeleton(&*take);
  return ResampleTake(*take, fps);
}

// --- BVH -----------------------------------------------------------------------------------

void BvhSeeds(const fs::path& out, const std::string& mocap) {
  const fs::path dir = out / "bvh_parser";
  const std::string custom = ReadText(kSourceDir + "/tests/data/import/custom_zxy.bvh.txt");
  WriteSeed(dir, "seed-custom-zxy.bvh", custom);
  WriteSeed(dir, "seed-custom-zxy-crlf.bvh", WithCrLf(custom));
  WriteSeed(dir, "seed-minimal.bvh",
            "HIERARCHY\nROOT r\n{\n\tOFFSET 0 0 0\n\tCHANNELS 3 Xrotation Yrotation Zrotation\n"
            "\tEnd Site\n\t{\n\t\tOFFSET 0 1 0\n\t}\n}\nMOTION\nFrames: 2\n"
            "Frame Time: 0.0083333\n0 0 0\n10 -20 30.5\n");
  if (mocap.empty()) return;
  for (const std::string name : {"bvh/05_01", "bvh/02_01", "bvh/09_06", "bvh_daz/02_01"}) {
    const std::string text = ReadText(mocap + "/" + name + ".bvh");
    std::string stem = name;
    for (char& c : stem) c = c == '/' ? '-' : c;
    WriteSeed(dir, "mocap-" + stem + ".bvh", TruncatedBvh(text, 8));
  }
}

// --- ASF and AMC ---------------------------------------------------------------------------

void AsfSeeds(const fs::path& out, const std::string& mocap) {
  const fs::path dir = out / "asf_parser";
  const std::string tiny = ReadText(kSourceDir + "/tests/data/import/tiny.asf.txt");
  WriteSeed(dir, "seed-tiny.asf", tiny);
  WriteSeed(dir, "seed-tiny-crlf.asf", WithCrLf(tiny));
  WriteSeed(dir, "seed-radians.asf",
            ":units\n  length 1\n  angle rad\n:root\n  order RZ RY RX TX TY TZ\n  axis ZYX\n"
            "  position 0 1 0\n  orientation 0.1 0.2 0.3\n:bonedata\n  begin\n    id 1\n"
            "    name a\n    direction 0 1 0\n    length 1\n    axis 0.5 0 0 XZY\n"
            "    dof rx ry rz l\n  end\n  begin\n    id 2\n    name b\n    direction 1 0 0\n"
            "    length 2\n    axis 0 0 0 XYZ\n    dof tx ty tz\n  end\n:hierarchy\n  begin\n"
            "    root a\n    a b\n  end\n");
  if (mocap.empty()) return;
  for (const std::string name : {"asfamc/05/05.asf", "asfamc/07/07-walk.asf"}) {
    std::string stem = fs::path(name).stem().string();
    WriteSeed(dir, "mocap-" + stem + ".asf", ReadText(mocap + "/" + name));
  }
}

// Motions for amc_parser_fuzz.cc's built-in skeleton: root (6 dofs), thigh (rx ry rz), shin
// (rx), spine (rz rx tx), toe (ry l), neck (ty tz); hip has no dofs.
std::string AmcMotion(int frames, int first_frame, bool radians, bool reversed) {
  std::string text = "#!OML:ASF fuzz.asf\n:FULLY-SPECIFIED\n";
  text += radians ? ":RADIANS\n" : ":DEGREES\n";
  for (int frame_idx = 0; frame_idx < frames; ++frame_idx) {
    const double t = frame_idx;
    auto line = [](const char* format, auto... values) {
      char buffer[160];
      std::snprintf(buffer, sizeof(buffer), format, values...);
      return std::string(buffer);
    };
    std::vector<std::string> lines = {line("root %.4f %.4f %.4f %.4f %.4f %.4f\n", 1 + 0.1 * t,
                                           17.5, -2 + 0.05 * t, 3 * t, -10 + t, 0.5),
                                      line("thigh %.4f %.4f %.4f\n", -30 + t, 5.25, 10 - t),
                                      line("shin %.4f\n", 45 + 2 * t),
                                      line("spine %.4f %.4f %.4f\n", 15.0, -25 + t, 0.5),
                                      line("toe %.4f %.4f\n", 20 * t, 1.5),
                                      line("neck %.4f %.4f\n", 0.1, -0.2)};
    if (reversed) std::reverse(lines.begin(), lines.end());
    text += std::to_string(first_frame + frame_idx) + "\n";
    for (const std::string& bone_line : lines) text += bone_line;
  }
  return text;
}

void AmcSeeds(const fs::path& out) {
  const fs::path dir = out / "amc_parser";
  WriteSeed(dir, "seed-three-frames.amc", AmcMotion(3, 1, false, false));
  WriteSeed(dir, "seed-radians-reversed.amc", AmcMotion(2, 0, true, true));
  WriteSeed(dir, "seed-crlf.amc", WithCrLf(AmcMotion(12, 1, false, false)));
}

// --- Motion archive ------------------------------------------------------------------------

std::string WriteArchive(const fs::path& work, const std::string& name,
                         const std::vector<ClipFrames>& commit_1,
                         const std::vector<ClipFrames>& commit_2, const Skeleton& skeleton,
                         double fps, const FrameFileWriterOptions& options) {
  const std::string path = (work / name).string();
  fs::remove(path);
  {
    Result<std::unique_ptr<FrameFileWriter>> writer =
        FrameFileWriter::Create(path, skeleton, fps, options);
    Check(writer.status(), "creating " + path);
    for (const ClipFrames& clip : commit_1) Check((*writer)->AppendClip(clip), "appending");
    Check((*writer)->Commit(), "committing " + path);
  }
  if (!commit_2.empty()) {
    Result<std::unique_ptr<FrameFileWriter>> writer = FrameFileWriter::OpenForAppend(path, options);
    Check(writer.status(), "opening " + path);
    for (const ClipFrames& clip : commit_2) Check((*writer)->AppendClip(clip), "appending");
    Check((*writer)->Commit(), "committing " + path);
  }
  std::string bytes = ReadText(path);
  fs::remove(path);
  return bytes;
}

ClipFrames ClipOf(const Take& take, const std::string& name) {
  ClipFrames clip = TakeToClipFrames(take);
  clip.info.name = name;
  return clip;
}

void FrameFileSeeds(const fs::path& out, const fs::path& work, const std::string& mocap) {
  const fs::path dir = out / "frame_file_reader";
  WriteSeed(dir, "seed-spec-example.mfs.bin",
            ReadText(kSourceDir + "/tests/data/frame_file/tiny.mfs.golden"));
  // The importer fixture: 4 joints, 3 frames at 30 fps.
  const Take custom =
      TakeFromBvh(ReadText(kSourceDir + "/tests/data/import/custom_zxy.bvh.txt"), "c", 30);
  FrameFileWriterOptions small_blocks;
  small_blocks.block_frames = 2;
  WriteSeed(
      dir, "seed-custom-blocks-of-2.mfs.bin",
      WriteArchive(work, "a.mfs", {ClipOf(custom, "c")}, {}, custom.skeleton, 30, small_blocks));
  FrameFileWriterOptions lossless = small_blocks;
  lossless.lossless = true;
  WriteSeed(dir, "seed-custom-lossless.mfs.bin",
            WriteArchive(work, "b.mfs", {ClipOf(custom, "c")}, {}, custom.skeleton, 30, lossless));
  // Two commits: both slots in use, two clips.
  WriteSeed(dir, "seed-custom-appended.mfs.bin",
            WriteArchive(work, "c.mfs", {ClipOf(custom, "c1")}, {ClipOf(custom, "c2")},
                         custom.skeleton, 30, small_blocks));
  if (mocap.empty()) return;
  const Take walk = TakeFromBvh(TruncatedBvh(ReadText(mocap + "/bvh/02_01.bvh"), 20), "02_01", 120);
  FrameFileWriterOptions blocks_of_8;
  blocks_of_8.block_frames = 8;
  WriteSeed(
      dir, "mocap-02_01-20-frames.mfs.bin",
      WriteArchive(work, "d.mfs", {ClipOf(walk, "02_01")}, {}, walk.skeleton, 120, blocks_of_8));
}

// --- Trellis -------------------------------------------------------------------------------

// A trellis of `frame_count` columns: column t holds the frames near t (runs of consecutive
// frames, some gaps, some empty columns), distances spread over [0, eps].
std::string WriteTrellis(const fs::path& work, uint64_t frame_count, uint32_t block_columns,
                         uint32_t k_max, const std::string& search_params) {
  const std::string path = (work / "t.mtr").string();
  fs::remove(path);
  fs::remove(TrellisFileWriter::PartialPath(path));
  TrellisParams params;
  params.frame_count = frame_count;
  params.archive_identity = 0x0123456789abcdefull;
  params.eps = 0.75f;
  params.k_max = k_max;
  params.exclusion_frames = 2;
  params.search_params = search_params;
  TrellisFileWriterOptions options;
  options.block_columns = block_columns;
  Result<std::unique_ptr<TrellisFileWriter>> writer =
      TrellisFileWriter::OpenOrResume(path, params, options);
  Check(writer.status(), "creating " + path);
  for (uint64_t first = 0; first < frame_count; first += block_columns) {
    std::vector<std::vector<Neighbour>> columns;
    for (uint64_t column = first; column < std::min<uint64_t>(frame_count, first + block_columns);
         ++column) {
      std::vector<Neighbour> neighbours;
      if (column % 7 != 3) {
        for (uint64_t frame = 0; frame < frame_count && neighbours.size() < k_max; ++frame) {
          const uint64_t gap = frame > column ? frame - column : column - frame;
          if (gap < 3 || (gap > 9 && gap < 13)) {
            const float distance =
                params.eps * static_cast<float>((frame * 37 + column) % 101) / 100.0f;
            neighbours.push_back({static_cast<uint32_t>(frame), distance});
          }
        }
      }
      columns.push_back(std::move(neighbours));
    }
    Check((*writer)->AppendBlock(columns), "appending to " + path);
  }
  Check((*writer)->Finish(), "finishing " + path);
  std::string bytes = ReadText(path);
  fs::remove(path);
  return bytes;
}

void TrellisSeeds(const fs::path& out, const fs::path& work) {
  const fs::path dir = out / "trellis_file_reader";
  WriteSeed(dir, "seed-spec-example.mtr.bin",
            ReadText(kSourceDir + "/tests/data/trellis_file/tiny.mtr.golden"));
  WriteSeed(dir, "seed-20-columns-blocks-of-8.mtr.bin", WriteTrellis(work, 20, 8, 6, "exact"));
  WriteSeed(dir, "seed-40-columns-blocks-of-16.mtr.bin",
            WriteTrellis(work, 40, 16, 10, "lsh tables=8 hashes=12 width=0.6 probes=2"));
  WriteSeed(dir, "seed-5-columns-one-block.mtr.bin", WriteTrellis(work, 5, 4096, 2, ""));
}

// --- Paths ---------------------------------------------------------------------------------

void PathsSeeds(const fs::path& out) {
  const fs::path dir = out / "paths_file_reader";
  PathsParams params;  // the spec's worked example
  params.trellis_identity = 0x1122334455667788ull;
  params.archive_identity = 0x0123456789abcdefull;
  params.frame_count = 1000;
  params.branch = 5;
  params.min_length = 60;
  params.all_branches = true;
  const std::vector<PathCandidate> example = {{100, 180, 500, 570, 100, 500},
                                              {100, 190, 500, 575, 100, 500},
                                              {500, 570, 100, 180, 500, 100}};
  Result<std::string> bytes = EncodePathsFile(params, example);
  Check(bytes.status(), "encoding the paths example");
  WriteSeed(dir, "seed-spec-example.mpa.bin", *bytes);

  params.all_branches = false;
  params.min_length = 4;
  params.frame_count = 400;
  std::vector<PathCandidate> many;
  for (uint64_t top = 0; top + 20 < params.frame_count; top += 9) {
    const uint64_t match = (top * 7 + 50) % 360;
    many.push_back({top, top + 4 + top % 11, match, match + 5 + top % 3, top, match});
  }
  bytes = EncodePathsFile(params, many);
  Check(bytes.status(), "encoding the paths seed");
  WriteSeed(dir, "seed-43-candidates.mpa.bin", *bytes);
  bytes = EncodePathsFile(params, {});
  Check(bytes.status(), "encoding the empty paths seed");
  WriteSeed(dir, "seed-empty.mpa.bin", *bytes);
}

}  // namespace
}  // namespace motif

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  if (argc != 2 && !(argc == 4 && std::string(argv[2]) == "--mocap")) {
    std::fprintf(stderr, "usage: fuzz_seed_maker OUT_DIR [--mocap DIR]\n");
    return 2;
  }
  const fs::path out = argv[1];
  const std::string mocap = argc == 4 ? argv[3] : "";
  const fs::path work = out / ".work";
  fs::create_directories(work);
  motif::BvhSeeds(out, mocap);
  motif::AsfSeeds(out, mocap);
  motif::AmcSeeds(out);
  motif::FrameFileSeeds(out, work, mocap);
  motif::TrellisSeeds(out, work);
  motif::PathsSeeds(out);
  fs::remove_all(work);
  return 0;
}
