// mine_archive --out OUT [--synth-frames N] [--synth-motifs M] [INPUT...]: mines takes, folders or
// an archive with the motifmine library (a small built-in synthetic archive without INPUT) and
// prints each motif's instances. An example of a downstream program:
// examples/mine_archive/CMakeLists.txt.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <motifmine/motifmine.h>

int main(int argc, char** argv) {
  motifmine::MineOptions options;
  options.write_report = false;
  std::vector<std::string> inputs;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc) {
      options.out_dir = argv[++i];
    } else if (arg == "--synth-frames" && i + 1 < argc) {
      options.synth_frames = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "--synth-motifs" && i + 1 < argc) {
      options.synth_motifs = static_cast<uint32_t>(std::strtoul(argv[++i], nullptr, 10));
    } else {
      inputs.push_back(arg);
    }
  }
  if (options.out_dir.empty()) {
    std::fprintf(
        stderr, "usage: mine_archive --out OUT [--synth-frames N] [--synth-motifs M] [INPUT...]\n");
    return 2;
  }
  options.progress = [](const std::string& stage, uint64_t done, uint64_t total) {
    if (done == total) std::fprintf(stderr, "%s: done\n", stage.c_str());
  };
  motifmine::MineResult result;
  const motifmine::Status status = motifmine::Mine(inputs, options, &result);
  if (!status.ok()) {
    std::fprintf(stderr, "mine_archive: %s\n", status.ToString().c_str());
    return static_cast<int>(status.code());
  }
  std::printf("%zu clips, eps %.3f (%s): %zu motifs\n", result.clips.size(), result.parameters.eps,
              result.parameters.eps_how.c_str(), result.motifs.size());
  for (const motifmine::Motif& motif : result.motifs) {
    std::printf("motif %u:", motif.id);
    for (const motifmine::Instance& instance : motif.instances) {
      std::printf(" %s [%llu, %llu)", instance.clip.c_str(),
                  static_cast<unsigned long long>(instance.start),
                  static_cast<unsigned long long>(instance.end));
    }
    std::printf("\n");
  }
  return 0;
}
