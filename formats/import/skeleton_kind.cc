#include "formats/import/skeleton_kind.h"

#include <filesystem>
#include <fstream>

#include "formats/import/asf_parser.h"
#include "formats/import/bvh_parser.h"
#include "formats/motion/canonical_skeleton.h"

namespace motif {
namespace {

// The start of a BVH file, through its MOTION keyword (or the whole file if it has none).
Result<std::string> ReadBvhHead(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    return ReadTakeFile(path).status();  // its message for a missing or special file
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return ReadTakeFile(path).status();
  std::string head;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    const size_t searched_from = head.size() < 8 ? 0 : head.size() - 8;
    head.append(chunk, static_cast<size_t>(in.gcount()));
    if (head.find("MOTION", searched_from) != std::string::npos) break;
    if (head.size() > kMaxTakeFileBytes) break;
  }
  return head;
}

Result<Skeleton> ReadSkeleton(const TakeSource& source, const ImportOptions& options) {
  if (source.format == TakeFormat::kBvh) {
    MOTIF_ASSIGN_OR_RETURN(std::string head, ReadBvhHead(source.path));
    return ParseBvhSkeleton(head, source.path);
  }
  const std::string& asf_path = source.asf_path.empty() ? options.asf_path : source.asf_path;
  if (asf_path.empty()) return Status::InvalidArgument(source.path + ": no ASF skeleton");
  MOTIF_ASSIGN_OR_RETURN(std::string text, ReadTakeFile(asf_path));
  MOTIF_ASSIGN_OR_RETURN(AsfSkeleton asf, ParseAsf(text, asf_path));
  return AsfToSkeleton(asf);
}

}  // namespace

Result<std::string> ReadSkeletonKind(const TakeSource& source, const ImportOptions& options) {
  Take take;
  MOTIF_ASSIGN_OR_RETURN(take.skeleton, ReadSkeleton(source, options));
  if (CanonicalizeSkeleton(&take)) return std::string(kCmuFamily);
  std::string kind = "custom:";
  for (const Joint& joint : take.skeleton.joints()) {
    kind += joint.name + "<" + std::to_string(joint.parent) + ";";
  }
  return kind;
}

}  // namespace motif
