// The options of each stage, made from a run's MineOptions (option_table.h) in one place: the
// trellis's, the grower's, the clustering's, the synthetic archive's and the report's. λ and the
// exclusion radius are resolved here into frames at the archive's rate, once; ε and the LSH
// family are resolved by the trellis stage from the data and recorded in the trellis file
// (TrellisReport), and the later stages and runs read them from there.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>

#include "common/status.h"
#include "engine/cluster/motif_clusterer.h"
#include "engine/grow/paths_builder.h"
#include "engine/lsh/lsh_options.h"
#include "engine/report/report_html.h"
#include "engine/synth/motion_synthesizer.h"
#include "engine/trellis/trellis_builder.h"
#include "motifmine/options.h"

namespace motif {

// λ in frames at `fps`: the frames given, else the seconds at that rate (at least 1 frame).
uint64_t ResolvedMinLengthFrames(const motifmine::MineOptions& options, double fps);

// The same-clip exclusion radius: the one given, else half of λ (the seconds given at `fps`,
// rounded; or half the frames given, rounded up).
uint32_t ResolvedExclusionFrames(const motifmine::MineOptions& options, double fps);

// The LSH options as given (hashes and width 0: chosen by the trellis stage from the data).
Result<LshOptions> LshOptionsFor(const motifmine::MineOptions& options);

// The trellis stage's options for an archive at `fps` (λ and the exclusion resolved). The
// archive version, the callbacks and the ranks are the session's, set by the pipeline.
// InvalidOption for an unknown search, ε rule or LSH ranking.
Result<TrellisOptions> TrellisOptionsFor(const motifmine::MineOptions& options, double fps);

// The grower's, with λ in frames.
PathsOptions PathsOptionsFor(const motifmine::MineOptions& options, double fps);

// The clustering's (its archive, progress and the grower's λ are set by the stage).
Result<ClusterOptions> ClusterOptionsFor(const motifmine::MineOptions& options);

// The built-in synthetic archive's (no inputs): `motifmine mine`'s planted motifs.
SynthOptions SynthOptionsFor(const motifmine::MineOptions& options);

ReportOptions ReportOptionsFor(const motifmine::MineOptions& options);

}  // namespace motif
