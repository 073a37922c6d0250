// The --names option of `motifmine export` and `export-motif`, and (included from here for
// them) reading a clip range back as a Take: formats/frame_file/clip_range_take.h.
// Thread-safety: pure functions (the reader's const methods are thread-safe).
#pragma once

#include <cstdint>
#include <string>

#include <boost/program_options.hpp>

#include "common/status.h"
#include "formats/frame_file/clip_range_take.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/motion/take.h"

namespace motif::cli {

// The --names option of export and export-motif: "source" (the default: the joints keep the
// names of the file the clip was imported from, where the import renamed them) or "canonical"
// (the archive's names).
void AddJointNamesOption(boost::program_options::options_description* options);
// Checks the option's value; false after printing a usage error naming the flag (exit 2).
bool CheckJointNamesOption(const std::string& command, const std::string& usage,
                           const boost::program_options::variables_map& vm);
// Renames `take`'s joints to the source's names when the option says so and the clip has them.
void ApplyJointNamesOption(const boost::program_options::variables_map& vm, Take* take);

}  // namespace motif::cli
