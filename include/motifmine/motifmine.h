// The motifmine library: mining motion motifs from motion-capture archives.
//
//   #include <motifmine/motifmine.h>
//
//   motifmine::MineOptions options;
//   options.out_dir = "out";
//   motifmine::MineResult result;
//   motifmine::Status status = motifmine::Mine({"takes/"}, options, &result);
//   if (!status.ok()) std::fprintf(stderr, "%s\n", status.ToString().c_str());
//
// Link with the CMake target motifmine::motifmine (docs/library.md).
#pragma once

#include "motifmine/archive.h"     // IWYU pragma: export
#include "motifmine/mine.h"        // IWYU pragma: export
#include "motifmine/signatures.h"  // IWYU pragma: export
#include "motifmine/status.h"      // IWYU pragma: export
