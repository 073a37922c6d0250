// instances.csv: the instances of a motifs.json document as one table, for spreadsheets and
// scripts (docs/formats/instances_csv.md): a header row, then one row per instance, motif by
// motif in motifs.json's order and, within a motif, in the order of its "instances":
//
//   motif,rank,clip,source,start,end,file_first_frame,file_last_frame,start_seconds,
//   end_seconds,distance
//
// start/end are clip frames (end exclusive), file_first_frame/file_last_frame the source file's
// frames of the first and last frame (FileFrameOf, both inclusive), the seconds are times in the
// source file, distance the warped distance to the motif's representative. Text fields are
// quoted as RFC 4180 says when they need it. Written by `motifmine mine` beside motifs.json.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/status.h"
#include "engine/cluster/motifs_json.h"

namespace motif {

// Each instance's rank within `motif` (indexed like its instances): 0 the representative, then
// by distance to it, ascending, ties to the instance listed first. Empty without a
// representative.
std::vector<uint32_t> InstanceRanks(const MotifsJsonMotif& motif);

// `value` as one CSV field: as it is, or, when it holds a comma, a double quote, CR or LF, in
// double quotes with each double quote doubled (RFC 4180, section 2).
std::string CsvField(std::string_view value);

// The whole file: the header row and one row per instance, each line ending in LF.
std::string InstancesCsvText(const MotifsDocument& document);

// Written atomically (temporary file, fsync, rename). IOError / ResourceExhausted naming the file.
Status WriteInstancesCsv(const std::string& path, const MotifsDocument& document);

}  // namespace motif
