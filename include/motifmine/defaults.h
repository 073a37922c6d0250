// The default of every mining option, defined once. motifmine::MineOptions (options.h) starts
// from these values, and so do the engine's own stage options (the trellis, the grower, the
// clustering, the LSH search), so a default changed here changes the tool, the library, the
// Python module and `reindex`'s first run together. What each option means: docs/guide.md,
// "motifmine mine", and the option table (`motifmine::MineOptionTable()`, options.h).
// Part of the public API; no third-party type.
#pragma once

#include <cstdint>

namespace motifmine::defaults {

// The radius ε: 0 means "chosen by the rule" (kEpsRule), as the pose distance of two poses whose
// every weighted joint differs by kEpsAngleDegrees (docs/design/algorithm.md, step 2).
inline constexpr double kEps = 0.0;
inline constexpr const char* kEpsRule = "joint-angle";
inline constexpr double kEpsAngleDegrees = 12.0;
// The trellis: neighbours kept per frame, the nearest; the same-clip exclusion radius in frames
// (0: half the minimum length); how the columns are found.
inline constexpr uint32_t kKMax = 256;
inline constexpr uint32_t kExclusionFrames = 0;
inline constexpr const char* kSearch = "auto";
// The LSH family (docs/design/lsh.md); 0 for hashes and width: chosen from the archive.
inline constexpr uint32_t kLshTables = 8;
inline constexpr uint32_t kLshHashes = 0;
inline constexpr double kLshWidth = 0.0;
inline constexpr double kLshWidthPerHash = 0.04;
inline constexpr uint32_t kLshProbes = 8;
inline constexpr uint32_t kLshMaxCandidates = 4096;
inline constexpr const char* kLshRanking = "sort";
inline constexpr uint32_t kLshMaxEntries = 16384;
inline constexpr uint32_t kLshChainColumns = 256;
inline constexpr uint32_t kLshChainedMaxCandidates = 6144;
inline constexpr uint32_t kLshChainProbeEvery = 4;
inline constexpr uint32_t kLshChainSweeps = 4;
// The grower: the branching factor B and the minimum length λ (0.5 s: 60 frames at 120 fps).
inline constexpr uint32_t kBranch = 5;
inline constexpr double kMinLengthSeconds = 0.5;
// The clustering: the motif count (0: automatic), the normalized cut's stopping Ncut, the least
// similarity of an edge, the split by length, and the pauses instances are trimmed at.
inline constexpr uint32_t kGroups = 0;
inline constexpr const char* kSimilarity = "warped";
inline constexpr double kMaxNcut = 0.5;
inline constexpr double kMinSimilarity = 0.1;
inline constexpr double kMaxLengthRatio = 3.0;
inline constexpr double kPauseSpeed = 15.0;  // degrees per second
inline constexpr double kPauseSeconds = 0.2;
// The run.
inline constexpr uint64_t kSeed = 1;
inline constexpr int kThreads = 0;  // all cores
inline constexpr uint64_t kSynthFrames = 120000;
inline constexpr uint32_t kSynthMotifs = 12;
inline constexpr uint32_t kPlaybackMegabytes = 32;

}  // namespace motifmine::defaults
