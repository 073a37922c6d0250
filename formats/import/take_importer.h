// Importing takes: finds BVH and ASF/AMC files under the paths a user gives, and turns each into a
// Take (formats/motion/take.h) with its skeleton mapped to the canonical CMU joint set where it is
// one (formats/motion/canonical_skeleton.h), rotations rest-aligned and relative to the parent.
//
// BVH: any hierarchy, channel order and rotation order, tabs or spaces, CRLF, any frame time.
// ASF/AMC: ASF units, bone axes and DOF order; AMC stores no rate (ImportOptions::amc_fps). An AMC
// file is paired with the ASF in its folder, or where a folder has several, the one whose name
// shares its subject prefix (13_17.amc with 13.asf, 07_05-walk.amc with 07-walk.asf);
// ImportOptions::asf_path names it outright. The pairing rule, for an AMC stem S whose subject
// P is the part of S before its first '_' (or '-'), and whose suffix X is the part from the first
// '-' after P (e.g. S = "07_05-walk": P = "07", X = "-walk"): the folder's only .asf if it has
// one; else the .asf whose stem is P + X, else the one whose stem is P (compared
// case-insensitively); else the only .asf whose stem before its first '-' is P. Anything else is
// InvalidArgument listing the folder's .asf files and suggesting --asf.
// Parsing details and accepted variants: bvh_parser.h, asf_parser.h, amc_parser.h. The T-pose a
// converter puts in front of a take (cgspeed BVH) is found by discontinuity: first_frame.h.
// Cross-format: a BVH take and the AMC take it was converted from import to the same rotations
// (to the BVH text's precision; tests/formats/import/cross_format_test.cc).
// Errors name the file, the line and the problem: "05_01.bvh:412: frame 3 has 95 values, the
// hierarchy declares 96 channels".
// Thread-safety: pure functions; takes may be imported from several threads at once.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/status.h"
#include "formats/motion/take.h"

namespace motif {

// The largest take (or ASF) file read: 1 GiB, far beyond any capture (a 31-joint BVH take of
// one hour at 120 fps is about 400 MB). A larger file is refused on its size, before it is read.
inline constexpr uint64_t kMaxTakeFileBytes = uint64_t{1} << 30;

// Reads a take or ASF file: ReadFileToString's errors (a folder, a FIFO, a device are refused
// without reading), and InvalidArgument naming the file and the limit for one larger than
// kMaxTakeFileBytes.
Result<std::string> ReadTakeFile(const std::string& path);

enum class FirstFramePolicy {
  kAuto,  // drop frame 0 when it is a converter's T-pose: discontinuous with the rest of the take
  kKeep,
  kDrop,
};

struct ImportOptions {
  double amc_fps = 120.0;  // AMC files store no rate; CMU captured at 120 Hz
  double bvh_fps = 0;      // > 0 overrides every BVH file's Frame Time
  std::string asf_path;    // if set, the skeleton for every AMC file
  FirstFramePolicy first_frame = FirstFramePolicy::kAuto;
  // Descriptions by take name (ReadTakeDescriptions): a take found here gets its description.
  std::unordered_map<std::string, std::string> descriptions;
};

enum class TakeFormat { kBvh, kAmc };

struct TakeSource {
  TakeFormat format = TakeFormat::kBvh;
  std::string path;      // the .bvh or .amc file
  std::string asf_path;  // for kAmc: the paired skeleton
  // For kAmc with no skeleton found: why (ImportTake fails with it, so that --skip-bad passes
  // over this take alone).
  std::string unpaired_reason;
};

// Expands files and folders (recursively, through linked folders, each folder entered once;
// sorted by path) into takes. A folder contributes its .bvh and .amc files (case-insensitive
// extensions); .asf files are used only as skeletons.
// Arguments keep their order; a file reached twice is listed once.
// NotFound for a missing path; InvalidArgument for a file that is not .bvh/.amc. An AMC file
// with no ASF to pair is listed with its unpaired_reason (the message says how to name one with
// --asf), and fails when imported.
Result<std::vector<TakeSource>> DiscoverTakes(const std::vector<std::string>& paths,
                                              const ImportOptions& options);

// Reads and converts one take. The take's name is the file stem, source_path its path as given,
// fps/source_fps the file's rate, content_hash XXH3-64 of the file's bytes (for AMC: of the AMC
// file's bytes). The skeleton is canonicalised (CanonicalizeSkeleton) and weights set.
// options.first_frame is applied before canonicalisation (kDrop on a one-frame take is an error).
// InvalidArgument (malformed input, naming file and line), NotFound, IOError.
Result<Take> ImportTake(const TakeSource& source, const ImportOptions& options);

}  // namespace motif
