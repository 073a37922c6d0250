#include "engine/pipeline/stage_options.h"

#include <cmath>

#include "engine/distance/epsilon_estimator.h"

namespace motif {

uint64_t ResolvedMinLengthFrames(const motifmine::MineOptions& options, double fps) {
  return options.min_length_frames > 0 ? options.min_length_frames
                                       : MinLengthFrames(options.min_length_seconds, fps);
}

uint32_t ResolvedExclusionFrames(const motifmine::MineOptions& options, double fps) {
  if (options.exclusion_frames > 0) return options.exclusion_frames;
  const double half = options.min_length_frames > 0
                          ? static_cast<double>(options.min_length_frames) / 2
                          : options.min_length_seconds * fps / 2;
  return static_cast<uint32_t>(std::lround(half));
}

Result<LshOptions> LshOptionsFor(const motifmine::MineOptions& options) {
  LshOptions lsh;
  lsh.tables = options.lsh_tables;
  lsh.hashes_per_table = options.lsh_hashes;
  lsh.bucket_width = static_cast<float>(options.lsh_width);
  lsh.width_per_hash = static_cast<float>(options.lsh_width_per_hash);
  lsh.probes_per_table = options.lsh_probes;
  lsh.max_candidates = options.lsh_max_candidates;
  lsh.max_entries = options.lsh_max_entries;
  lsh.chain_columns = options.lsh_chain_columns;
  lsh.chained_max_candidates = options.lsh_chained_max_candidates;
  lsh.chain_probe_every = options.lsh_chain_probe_every;
  lsh.chain_sweeps = options.lsh_chain_sweeps;
  if (!ParseLshRanking(options.lsh_ranking, &lsh.ranking)) {
    return Status::InvalidOption("ranking",
                                 "must be sort or code, not '" + options.lsh_ranking + "'");
  }
  lsh.seed = options.seed;
  lsh.threads = options.threads;
  return lsh;
}

Result<TrellisOptions> TrellisOptionsFor(const motifmine::MineOptions& options, double fps) {
  TrellisOptions trellis;
  trellis.eps = static_cast<float>(options.eps);
  Result<EpsilonRule> rule = ParseEpsilonRule(options.eps_rule);
  if (!rule.ok()) {
    return Status::InvalidOption("eps-rule",
                                 "must be joint-angle or paper, not '" + options.eps_rule + "'");
  }
  trellis.eps_rule = *rule;
  trellis.eps_joint_angle_degrees = options.eps_angle_degrees;
  trellis.k_max = options.k_max;
  trellis.exclusion_frames = ResolvedExclusionFrames(options, fps);
  Result<TrellisSearchMode> search = ParseTrellisSearchMode(options.search);
  if (!search.ok()) {
    return Status::InvalidOption("search",
                                 "must be auto, lsh or exact, not '" + options.search + "'");
  }
  trellis.search = *search;
  trellis.threads = options.threads;
  trellis.seed = options.seed;
  trellis.weights_path = options.weights_path;
  MOTIF_ASSIGN_OR_RETURN(trellis.lsh, LshOptionsFor(options));
  return trellis;
}

PathsOptions PathsOptionsFor(const motifmine::MineOptions& options, double fps) {
  PathsOptions paths;
  paths.branch = options.branch;
  paths.min_length_frames = ResolvedMinLengthFrames(options, fps);
  paths.all_branches = options.all_branches;
  return paths;
}

Result<ClusterOptions> ClusterOptionsFor(const motifmine::MineOptions& options) {
  ClusterOptions cluster;
  cluster.cut.groups = options.groups;
  cluster.cut.max_ncut = options.max_ncut;
  cluster.similarity.min_similarity = options.min_similarity;
  cluster.max_length_ratio = options.max_length_ratio;
  if (options.similarity != "warped" && options.similarity != "shared") {
    return Status::InvalidOption("similarity",
                                 "must be warped or shared, not '" + options.similarity + "'");
  }
  cluster.warped.enabled = options.similarity == "warped";
  cluster.pauses.max_speed = options.pause_speed;
  cluster.pauses.min_seconds = options.pause_seconds;
  cluster.seed = options.seed;
  cluster.threads = options.threads;
  return cluster;
}

SynthOptions SynthOptionsFor(const motifmine::MineOptions& options) {
  SynthOptions synth;
  // Background that does not repeat within eps, so the planted motifs are the only long repeats
  // and precision against them means something (docs/guide.md, synth).
  synth.background_variation_degrees = kRecommendedBackgroundVariation;
  synth.frames = options.synth_frames;
  synth.motifs = options.synth_motifs;
  synth.seed = options.seed;
  synth.threads = options.threads > 0 ? static_cast<uint32_t>(options.threads) : 0;
  return synth;
}

ReportOptions ReportOptionsFor(const motifmine::MineOptions& options) {
  ReportOptions report;
  report.playback_bytes = uint64_t{options.playback_mb} << 20;
  return report;
}

}  // namespace motif
