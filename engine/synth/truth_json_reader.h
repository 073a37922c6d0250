// Reads OUT.truth.json, the planted instances of a synthetic archive written by WriteTruthJson
// (motion_synthesizer.h): {"version": 1, "archive", "frames", "seed", "motifs",
// "instances": [{"clip", "start", "end", "motif", "warp", "nonuniform"}]}.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/synth/motion_synthesizer.h"

namespace motif {

struct TruthFile {
  std::string archive;
  uint64_t frames = 0;
  uint64_t seed = 0;
  uint32_t motifs = 0;
  std::vector<PlantedInstance> instances;
};

// InvalidArgument naming the field on a malformed file (missing field, wrong type, end <= start);
// NotSupported for another version; NotFound / IOError from reading.
Result<TruthFile> ParseTruthJson(const std::string& text, const std::string& name);
Result<TruthFile> ReadTruthJson(const std::string& path);

// Where an archive's truth is written: OUT.mfs -> OUT.truth.json.
std::string TruthPathFor(const std::string& archive_path);

}  // namespace motif
