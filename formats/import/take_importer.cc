#include "formats/import/take_importer.h"

#include <xxhash.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <new>
#include <set>
#include <utility>

#include "common/file_util.h"
#include "common/utf8.h"
#include "formats/import/amc_parser.h"
#include "formats/import/asf_parser.h"
#include "formats/import/bvh_parser.h"
#include "formats/import/first_frame.h"
#include "formats/import/text_scanner.h"
#include "formats/motion/canonical_skeleton.h"

namespace motif {
namespace {

namespace fs = std::filesystem;
using import_internal::EqualsIgnoreCase;

bool HasExtension(const fs::path& path, std::string_view extension) {
  return EqualsIgnoreCase(path.extension().string(), extension);
}

// Lists a folder's .asf files (sorted), caching per folder: a folder of AMC files is paired once.
class AsfFinder {
 public:
  explicit AsfFinder(const ImportOptions& options) : options_(options) {}

  Result<std::string> FindFor(const std::string& amc_path) {
    if (!options_.asf_path.empty()) return options_.asf_path;
    const fs::path amc(amc_path);
    const std::string folder = amc.has_parent_path() ? amc.parent_path().string() : ".";
    auto cached = folders_.find(folder);
    if (cached == folders_.end()) {
      std::vector<std::string> asf_files;
      std::error_code error;
      for (fs::directory_iterator it(folder, error), end; !error && it != end;
           it.increment(error)) {
        if (it->is_regular_file(error) && HasExtension(it->path(), ".asf")) {
          asf_files.push_back(it->path().string());
        }
      }
      if (error) return Status::IOError(folder + ": cannot list the folder: " + error.message());
      std::sort(asf_files.begin(), asf_files.end());
      cached = folders_.emplace(folder, std::move(asf_files)).first;
    }
    const std::vector<std::string>& asf_files = cached->second;
    const std::string hint = "; name the skeleton file (asf)";
    if (asf_files.empty()) {
      return Status::InvalidArgument(amc_path + ": no .asf skeleton in its folder to pair it with" +
                                     hint)
          .WithOption("asf");
    }
    if (asf_files.size() == 1) return asf_files[0];
    // Several skeletons: match the AMC's subject prefix, and its "-suffix" if it has one.
    const std::string stem = amc.stem().string();
    const size_t underscore = stem.find('_');
    const std::string subject = stem.substr(0, std::min(underscore, stem.find('-')));
    const size_t dash = stem.find('-', subject.size());
    std::vector<std::string> wanted;
    if (dash != std::string::npos) wanted.push_back(subject + stem.substr(dash));
    wanted.push_back(subject);
    for (const std::string& wanted_stem : wanted) {
      for (const std::string& asf : asf_files) {
        if (EqualsIgnoreCase(fs::path(asf).stem().string(), wanted_stem)) return asf;
      }
    }
    std::vector<std::string> same_subject;
    for (const std::string& asf : asf_files) {
      const std::string asf_stem = fs::path(asf).stem().string();
      if (EqualsIgnoreCase(asf_stem.substr(0, asf_stem.find('-')), subject)) {
        same_subject.push_back(asf);
      }
    }
    if (same_subject.size() == 1) return same_subject[0];
    std::string names;
    for (const std::string& asf : asf_files) {
      names += (names.empty() ? "" : ", ") + fs::path(asf).filename().string();
    }
    std::string expected;
    for (const std::string& wanted_stem : wanted) {
      expected += (expected.empty() ? "" : " or ") + wanted_stem + ".asf";
    }
    return Status::InvalidArgument(amc_path +
                                   ": cannot tell which skeleton goes with it: its folder has " +
                                   std::to_string(asf_files.size()) + " .asf files (" + names +
                                   "), none named " + expected + hint)
        .WithOption("asf");
  }

 private:
  const ImportOptions& options_;
  std::map<std::string, std::vector<std::string>> folders_;
};

class TakeCollector {
 public:
  explicit TakeCollector(const ImportOptions& options) : finder_(options) {}

  Status Add(const fs::path& path) {
    const std::string key = path.lexically_normal().string();
    if (!seen_.insert(key).second) return Status::Ok();
    TakeSource source;
    source.path = path.string();
    if (HasExtension(path, ".bvh")) {
      source.format = TakeFormat::kBvh;
    } else if (HasExtension(path, ".amc")) {
      source.format = TakeFormat::kAmc;
      Result<std::string> asf = finder_.FindFor(source.path);
      if (asf.ok()) {
        source.asf_path = *asf;
      } else if (asf.status().IsInvalidArgument()) {
        source.unpaired_reason = asf.status().message();
      } else {
        return asf.status();
      }
    } else {
      return Status::InvalidArgument(
                 source.path +
                 ": not a .bvh or .amc file (an .asf skeleton is paired with the AMC "
                 "files of its folder, or named by asf)")
          .WithOption("asf");
    }
    sources_.push_back(std::move(source));
    return Status::Ok();
  }

  // The folder's takes, in linked folders too; a folder reached again (a link back up the tree,
  // or two links to one folder) is not entered twice.
  Status AddFolder(const std::string& folder) {
    std::vector<fs::path> files;
    std::error_code error;
    std::set<fs::path> entered = {fs::canonical(folder, error)};
    for (fs::recursive_directory_iterator
             it(folder,
                fs::directory_options::skip_permission_denied |
                    fs::directory_options::follow_directory_symlink,
                error),
         end;
         !error && it != end; it.increment(error)) {
      std::error_code ignored;
      if (it->is_directory(ignored) &&
          !entered.insert(fs::canonical(it->path(), ignored)).second) {
        it.disable_recursion_pending();
        continue;
      }
      if (it->is_regular_file(error) &&
          (HasExtension(it->path(), ".bvh") || HasExtension(it->path(), ".amc"))) {
        files.push_back(it->path());
      }
    }
    if (error) return Status::IOError(folder + ": cannot list the folder: " + error.message());
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) MOTIF_RETURN_IF_ERROR(Add(file));
    return Status::Ok();
  }

  std::vector<TakeSource> Take() { return std::move(sources_); }

 private:
  AsfFinder finder_;
  std::set<std::string> seen_;
  std::vector<TakeSource> sources_;
};

Result<std::vector<TakeSource>> DiscoverTakesImpl(const std::vector<std::string>& paths,
                                                  const ImportOptions& options) {
  if (!options.asf_path.empty()) {
    std::error_code error;
    if (!fs::is_regular_file(options.asf_path, error)) {
      return Status::NotFound(options.asf_path + ": no such ASF skeleton file (asf)")
          .WithOption("asf");
    }
  }
  TakeCollector collector(options);
  for (const std::string& path : paths) {
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (!fs::exists(status)) return Status::NotFound(path + ": no such file or folder");
    if (fs::is_directory(status)) {
      MOTIF_RETURN_IF_ERROR(collector.AddFolder(path));
    } else {
      MOTIF_RETURN_IF_ERROR(collector.Add(fs::path(path)));
    }
  }
  return collector.Take();
}

// Names that reach the JSON outputs (the clip name and source path from the file's path, the
// joint names) must be UTF-8: refused here, named, rather than written into every file after.
Status CheckNamesAreUtf8(const std::string& path, const Skeleton& skeleton) {
  if (!IsValidUtf8(path)) {
    return Status::InvalidArgument(path + ": the file's path is not valid UTF-8; rename it");
  }
  for (const Joint& joint : skeleton.joints()) {
    if (!IsValidUtf8(joint.name)) {
      return Status::InvalidArgument(path + ": a joint name is not valid UTF-8");
    }
  }
  return Status::Ok();
}

}  // namespace

Result<std::string> ReadTakeFile(const std::string& path) {
  return ReadFileToString(path, kMaxTakeFileBytes);
}

namespace {

Result<Take> ImportTakeImpl(const TakeSource& source, const ImportOptions& options) {
  if (!IsValidUtf8(source.path)) return CheckNamesAreUtf8(source.path, Skeleton());
  MOTIF_ASSIGN_OR_RETURN(std::string text, ReadTakeFile(source.path));
  Take take;
  if (source.format == TakeFormat::kBvh) {
    MOTIF_ASSIGN_OR_RETURN(take, ParseBvh(text, source.path, options.bvh_fps));
  } else {
    const std::string& asf_path = source.asf_path.empty() ? options.asf_path : source.asf_path;
    if (asf_path.empty() && !source.unpaired_reason.empty()) {
      return Status::InvalidArgument(source.unpaired_reason).WithOption("asf");
    }
    if (asf_path.empty()) {
      return Status::InvalidArgument(source.path +
                                     ": no ASF skeleton given for this AMC file (asf)")
          .WithOption("asf");
    }
    MOTIF_ASSIGN_OR_RETURN(std::string asf_text, ReadTakeFile(asf_path));
    MOTIF_ASSIGN_OR_RETURN(AsfSkeleton asf, ParseAsf(asf_text, asf_path));
    MOTIF_ASSIGN_OR_RETURN(take, ParseAmc(asf, text, source.path, options.amc_fps));
  }
  MOTIF_RETURN_IF_ERROR(CheckNamesAreUtf8(source.path, take.skeleton));
  take.name = fs::path(source.path).stem().string();
  take.source_path = source.path;
  take.content_hash = XXH3_64bits(text.data(), text.size());
  if (auto described = options.descriptions.find(take.name);
      described != options.descriptions.end()) {
    take.description = described->second;
  }
  bool drop_first = false;
  switch (options.first_frame) {
    case FirstFramePolicy::kAuto:
      drop_first = CheckFirstFrame(take).discontinuous;
      break;
    case FirstFramePolicy::kKeep:
      drop_first = false;
      break;
    case FirstFramePolicy::kDrop:
      drop_first = true;
      break;
  }
  if (drop_first) {
    if (take.frame_count() < 2) {
      return Status::InvalidArgument(source.path +
                                     ": has a single frame, dropping the first leaves none");
    }
    DropFirstFrame(&take);
    take.source_first_frame = 1;
  }
  CanonicalizeSkeleton(&take);
  return take;
}

}  // namespace

Result<std::vector<TakeSource>> DiscoverTakes(const std::vector<std::string>& paths,
                                              const ImportOptions& options) {
  try {
    return DiscoverTakesImpl(paths, options);
  } catch (const std::bad_alloc&) {
    return Status::ResourceExhausted("out of memory while listing the takes to import");
  } catch (const std::exception& error) {
    return Status::IOError(std::string("listing the takes to import: ") + error.what());
  }
}

Result<Take> ImportTake(const TakeSource& source, const ImportOptions& options) {
  try {
    return ImportTakeImpl(source, options);
  } catch (const std::bad_alloc&) {
    return Status::ResourceExhausted(source.path + ": out of memory while importing");
  } catch (const std::exception& error) {
    return Status::IOError(source.path + ": " + error.what());
  }
}

}  // namespace motif
