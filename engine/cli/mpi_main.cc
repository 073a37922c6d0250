// motifmine-mpi: `mine` on the ranks of an MPI job (docs/design/distributed.md):
//   mpirun -np R motifmine-mpi mine ARCHIVE --out DIR [the options of motifmine mine]
// Every rank runs rank 0's command line; rank 0 prints and writes DIR, the others share the
// trellis's work. A rank that fails while others wait for it ends the job (MPI_Abort) after
// naming itself; a rank that dies is named by mpirun.
#include <malloc.h>
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "engine/cli/cli_common.h"
#include "engine/distributed/mpi_rank_group.h"

namespace {

void PrintUsage(FILE* out) {
  std::fprintf(out,
               "motifmine-mpi: motifmine's mining on the ranks of an MPI job.\n\n"
               "usage: mpirun -np R motifmine-mpi mine [INPUT...] --out DIR [options]\n"
               "       (the options of `motifmine mine`; motifmine-mpi mine --help lists them)\n\n"
               "Rank 0 writes DIR and prints; every rank reads the archive at the same path (a\n"
               "shared file system, or a copy on each node). --threads 0 (the default) gives\n"
               "each rank its share of its node's cores.\n");
}

// Rank 0's command line, on every rank: ranks launched with others (mpirun's MPMD form) then
// still parse the same options, and none waits for a step another skips.
std::vector<std::string> RankZerosArguments(int argc, char** argv, motif::MpiRankGroup* ranks) {
  std::string joined;
  for (int arg = 1; arg < argc; ++arg) joined += std::string(argv[arg]) + '\0';
  if (!ranks->Broadcast(&joined).ok()) MPI_Abort(MPI_COMM_WORLD, motif::cli::kExitInternal);
  std::vector<std::string> args;
  for (size_t start = 0; start < joined.size();) {
    const size_t end = joined.find('\0', start);
    args.push_back(joined.substr(start, end - start));
    start = end + 1;
  }
  return args;
}

int Run(int argc, char** argv, motif::MpiRankGroup* ranks) {
  using motif::cli::kExitOk;
  using motif::cli::kExitUsage;
  const std::vector<std::string> args = RankZerosArguments(argc, argv, ranks);
  const std::string name = args.empty() ? "" : args[0];
  if (name == "--help" || name == "-h" || name == "help") {
    if (ranks->rank() == 0) PrintUsage(stdout);
    return kExitOk;
  }
  if (name != "mine") {
    if (ranks->rank() == 0) {
      if (!name.empty())
        std::fprintf(stderr, "motifmine-mpi: unknown command '%s'\n", name.c_str());
      PrintUsage(stderr);
      return kExitUsage;
    }
    return kExitOk;  // rank 0's exit code is the job's
  }
  motif::cli::MineAcrossRanks across;
  across.ranks = ranks;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  across.default_threads = std::max(1, cores / ranks->ranks_on_this_node());
  across.abort_all = [](int code) { MPI_Abort(MPI_COMM_WORLD, code); };
  return motif::cli::RunMineAcrossRanks(std::vector<std::string>(args.begin() + 1, args.end()),
                                        across);
}

}  // namespace

int main(int argc, char** argv) {
  // As motifmine's main: large buffers mapped, so freeing returns them to the system.
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  int code = 0;
  {
    motif::MpiRankGroup ranks(MPI_COMM_WORLD);
    code = Run(argc, argv, &ranks);
  }
  MPI_Finalize();
  return code;
}
