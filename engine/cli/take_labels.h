// Labels of takes for `motifmine classify --labels FILE.tsv`: one take per line, its clip name
// (as `motifmine info` lists it) and its label, separated by a tab. Blank lines and lines starting
// with '#' are skipped, and so is a first line whose first field is "clip" (a header). Further
// fields after the label are ignored. scripts/mocap_labels.py writes such a file for the CMU
// takes from their INDEX.tsv descriptions.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/status.h"

namespace motif::cli {

struct TakeLabels {
  std::map<std::string, std::string> by_clip;
};

// NotFound: no file. InvalidArgument naming the file and line: a line without a tab-separated
// label, an empty clip or label, a clip listed twice.
Result<TakeLabels> ReadTakeLabels(const std::string& path);

}  // namespace motif::cli
