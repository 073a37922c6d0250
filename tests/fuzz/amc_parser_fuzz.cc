// Fuzz target: the AMC parser (formats/import/amc_parser.h) on arbitrary text, against a fixed
// skeleton (kSkeletonAsf below: the importer tests' tests/data/import/tiny.asf.txt with two more
// bones, so that every kind of dof, a bone without dofs and a translation-only bone appear),
// and every take it accepts through the rest of the import (tests/fuzz/import_pipeline.h).
// Promise checked: no crash, leak or undefined behaviour; errors are InvalidArgument naming the
// file. Seeds: tests/data/fuzz/amc_parser/ (motions for this skeleton).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "formats/import/amc_parser.h"
#include "formats/import/asf_parser.h"
#include "tests/fuzz/fuzz_support.h"
#include "tests/fuzz/import_pipeline.h"

namespace {

constexpr std::string_view kSkeletonAsf = R"(:version 1.10
:name fuzz
:units
  mass 1.0
  length 0.45
  angle deg
:root
   order TX TY TZ RX RY RZ
   axis XYZ
   position 0 0 0
   orientation 0 0 0
:bonedata
  begin
     id 1
     name hip
     direction 1 0 0
     length 2
     axis 0 0 0  XYZ
  end
  begin
     id 2
     name thigh
     direction 0 -1 0
     length 6
     axis 0 0 20  XYZ
    dof rx ry rz
  end
  begin
     id 3
     name shin
     direction 0 -1 0
     length 5
     axis 0 0 20  XYZ
    dof rx
  end
  begin
     id 4
     name spine
     direction 0 1 0
     length 4
     axis 10 -5 30  ZYX
    dof rz rx tx
  end
  begin
     id 5
     name toe
     direction 0 0 1
     length 1
     axis 0 90 0  YZX
    dof ry l
  end
  begin
     id 6
     name neck
     direction 0 1 0
     length 1
     axis 0 0 0  XYZ
    dof ty tz
  end
:hierarchy
  begin
    root hip spine
    hip thigh
    thigh shin
    shin toe
    spine neck
  end
)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace motif;
  static const AsfSkeleton* const asf = [] {
    Result<AsfSkeleton> parsed = ParseAsf(kSkeletonAsf, "fuzz_skeleton.asf");
    if (!parsed.ok()) fuzz::Fail("the built-in skeleton", parsed.status().ToString());
    return new AsfSkeleton(std::move(parsed).value());
  }();
  static const std::string kFileName = "fuzz.amc";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Result<Take> take = ParseAmc(*asf, text, kFileName, fuzz::kArchiveFps);
  if (!take.ok()) {
    fuzz::CheckError(take.status(), Status::Code::kInvalidArgument, kFileName, "ParseAmc");
    return 0;
  }
  fuzz::ImportParsedTake(std::move(take).value());
  return 0;
}
