// Fuzz target: the BVH parser (formats/import/bvh_parser.h) on arbitrary text, and every take
// it accepts through the rest of the import (tests/fuzz/import_pipeline.h).
// Promise checked: no crash, leak or undefined behaviour; errors are InvalidArgument naming the
// file. Seeds: tests/data/fuzz/bvh_parser/ (fuzz_seed_maker writes more from the CMU takes).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "formats/import/bvh_parser.h"
#include "tests/fuzz/fuzz_support.h"
#include "tests/fuzz/import_pipeline.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace motif;
  static const std::string kFileName = "fuzz.bvh";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Result<Take> take = ParseBvh(text, kFileName);
  if (!take.ok()) {
    fuzz::CheckError(take.status(), Status::Code::kInvalidArgument, kFileName, "ParseBvh");
    return 0;
  }
  fuzz::ImportParsedTake(std::move(take).value());
  return 0;
}
