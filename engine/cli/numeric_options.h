// Checks of the numbers given on a command line, for every command at once: boost's parser
// turns "--kmax=-1" into 4294967295 and reads "nan" and "inf" as numbers, so a negative count,
// a number that is not finite would otherwise run (or allocate without bound). The options of
// the option table have their own ranges (table_options.h). Called by ParseCommand; a failed
// check is a usage error (exit code 2).
#pragma once

#include <boost/program_options.hpp>

#include "common/status.h"

namespace motif::cli {

// Every option of `parsed` that the user gave: an unsigned option must not be negative, a
// floating-point one must be finite, a frame rate (--fps, --bvh-fps, --amc-fps) 0 where 0 means
// "not given", else within [1, 10000]; synth's --frames at most 10^8; reindex's --min-age >= 0.
// The message names the flag and the value.
Status CheckNumericOptions(const boost::program_options::parsed_options& parsed,
                           const boost::program_options::variables_map& vm);

}  // namespace motif::cli
