// Fuzz target: the ASF parser (formats/import/asf_parser.h) on arbitrary text, the joint
// skeleton built from every skeleton it accepts (AsfToSkeleton), and a two-frame AMC motion
// written for that skeleton, parsed (formats/import/amc_parser.h) and run through the rest of
// the import (tests/fuzz/import_pipeline.h): bone axes, dof lists and the hierarchy are what
// the fuzzer varies, the motion is fixed.
// Promise checked: no crash, leak or undefined behaviour; errors are InvalidArgument naming the
// file. Seeds: tests/data/fuzz/asf_parser/.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "formats/import/amc_parser.h"
#include "formats/import/asf_parser.h"
#include "tests/fuzz/fuzz_support.h"
#include "tests/fuzz/import_pipeline.h"

namespace {

// Frame 1 all zero; frame 2 small distinct values (a rotation of each dof, a translation).
std::string MotionFor(const motif::AsfSkeleton& asf) {
  std::string text = ":FULLY-SPECIFIED\n:DEGREES\n";
  for (int frame = 1; frame <= 2; ++frame) {
    text += std::to_string(frame) + "\n";
    auto add_line = [&](const std::string& name, size_t dof_count) {
      text += name;
      for (size_t dof_idx = 0; dof_idx < dof_count; ++dof_idx) {
        text += ' ';
        text += frame == 1 ? std::string("0") : std::to_string(5 * (dof_idx + 1)) + ".5";
      }
      text += "\n";
    };
    add_line("root", asf.root_order.size());
    for (const motif::AsfBone& bone : asf.bones) {
      if (!bone.dofs.empty()) add_line(bone.name, bone.dofs.size());
    }
  }
  return text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace motif;
  static const std::string kAsfName = "fuzz.asf";
  static const std::string kAmcName = "fuzz.amc";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Result<AsfSkeleton> asf = ParseAsf(text, kAsfName);
  if (!asf.ok()) {
    fuzz::CheckError(asf.status(), Status::Code::kInvalidArgument, kAsfName, "ParseAsf");
    return 0;
  }
  const Skeleton skeleton = AsfToSkeleton(*asf);
  if (skeleton.joint_count() != asf->bones.size() + 1) {
    fuzz::Fail("AsfToSkeleton", std::to_string(skeleton.joint_count()) + " joints for " +
                                    std::to_string(asf->bones.size()) + " bones");
  }
  Result<Take> take = ParseAmc(*asf, MotionFor(*asf), kAmcName, fuzz::kArchiveFps);
  if (!take.ok()) {
    fuzz::CheckError(take.status(), Status::Code::kInvalidArgument, kAmcName, "ParseAmc");
    return 0;
  }
  fuzz::ImportParsedTake(std::move(take).value());
  return 0;
}
