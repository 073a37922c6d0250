// Take descriptions from an index file the user gives (`import --descriptions`, `mine
// --descriptions`): a tab-separated table with a header line naming at least the columns `file`
// (a take file's path or name; its stem is the clip name) and `description`, one take a line, as
// ../shared/data/mocap/INDEX.tsv is. Blank lines and lines starting with '#' are skipped.
// Thread-safety: pure functions.
#pragma once

#include <string>
#include <unordered_map>

#include "common/status.h"

namespace motif {

// Description by clip name (the stem of `file`). InvalidArgument naming the file and the line:
// no `file` or `description` column, a line with too few columns, a name given twice with two
// descriptions, text that is not UTF-8. IOError when it cannot be read.
Result<std::unordered_map<std::string, std::string>> ReadTakeDescriptions(const std::string& path);

}  // namespace motif
