// motifmine: the command-line tool. Dispatches to one command per file in engine/cli/.
#include <malloc.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "common/temporary_files.h"
#include "engine/cli/cli_common.h"

namespace {

struct Command {
  const char* name;
  int (*run)(const std::vector<std::string>&);
  const char* summary;
};

const Command kCommands[] = {
    {"mine", motif::cli::RunMine,
     "the whole job: trellis, paths, motifs and report (synthetic demo without INPUT)"},
    {"reindex", motif::cli::RunReindex,
     "cron job: import new takes of a folder, update the trellis incrementally, re-mine, switch "
     "atomically"},
    {"import", motif::cli::RunImport,
     "import BVH or ASF/AMC takes into an archive (creates or appends)"},
    {"info", motif::cli::RunInfo, "describe an archive: clips, frames, skeleton, size"},
    {"verify", motif::cli::RunVerify, "check every checksum of an archive"},
    {"export", motif::cli::RunExport, "write a clip (or a frame range of it) as a BVH file"},
    {"synth", motif::cli::RunSynth, "write a synthetic archive with planted motifs and its truth"},
    {"trellis", motif::cli::RunTrellis,
     "build the matching trellis (LSH eps-NN) of an archive, or audit it"},
    {"inspect-trellis", motif::cli::RunInspectTrellis, "print one column of a trellis"},
    {"grow", motif::cli::RunGrow, "grow the trellis's continuous paths into motif candidates"},
    {"cluster", motif::cli::RunCluster,
     "cluster the grown paths into motifs (normalized cut): motifs.json"},
    {"report", motif::cli::RunReport,
     "write the HTML report of motifs.json: overview, timeline, stick figures"},
    {"score", motif::cli::RunScore,
     "score motifs.json against annotated or planted occurrences (precision, recall)"},
    {"export-motif", motif::cli::RunExportMotif, "write every instance of one motif as a BVH file"},
    {"words", motif::cli::RunWords,
     "motion words: train their embedding, cluster motifs, write every take's signature"},
    {"search", motif::cli::RunSearch,
     "find the motions most like a clip range or a BVH file (signatures, EMD)"},
    {"classify", motif::cli::RunClassify,
     "classify the takes by their signatures: MDS + k-means, kNN with labels"},
    {"segment", motif::cli::RunSegment,
     "cut takes into segments of one activity by their signatures (kNN with labels, or not)"},
    {"graph", motif::cli::RunGraph,
     "a motion graph with signature-constrained transitions, and a random walk through it"},
};

void PrintUsage(FILE* out) {
  std::fprintf(out,
               "motifmine: mines recurring motion motifs from large motion-capture archives.\n\n"
               "usage: motifmine COMMAND [ARGS...]   (motifmine COMMAND --help for details)\n\n"
               "commands:\n");
  for (const Command& command : kCommands) {
    std::fprintf(out, "  %-16s %s\n", command.name, command.summary);
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Clip and block buffers are megabytes each, allocated on worker threads and freed on another.
  // glibc's adaptive threshold would soon serve them from per-thread heaps, whose fragmentation
  // lets the peak memory of a long streaming run creep up with N; a fixed threshold keeps them
  // mmapped, so freeing returns them to the system and the peak stays flat.
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  motif::RemoveTemporaryFilesOnTermination();  // a SIGTERM or Ctrl-C leaves no temporary file
  if (argc < 2) {
    PrintUsage(stderr);
    return motif::cli::kExitUsage;
  }
  const std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    PrintUsage(stdout);
    return motif::cli::kExitOk;
  }
  if (name == "--version") {
    std::printf("motifmine %s\n", MOTIFMINE_VERSION);
    return motif::cli::kExitOk;
  }
  std::vector<std::string> args(argv + 2, argv + argc);
  for (const Command& command : kCommands) {
    if (name == command.name) {
      try {
        return command.run(args);
      } catch (const std::exception& error) {
        std::fprintf(stderr, "motifmine %s: internal error: %s\n", command.name, error.what());
        return motif::cli::kExitInternal;
      }
    }
  }
  std::fprintf(stderr, "motifmine: unknown command '%s'\n\n", name.c_str());
  PrintUsage(stderr);
  return motif::cli::kExitUsage;
}
