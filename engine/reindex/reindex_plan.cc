#include "engine/reindex/reindex_plan.h"

#include <filesystem>

#include "engine/pipeline/option_table.h"
#include "engine/pipeline/stage_options.h"
#include "engine/trellis/search_cache.h"
#include "engine/trellis/trellis_builder.h"

namespace motif {
namespace {

namespace fs = std::filesystem;

bool Given(const std::set<std::string>& given, const char* name) { return given.count(name) > 0; }

// The trellis-determining part of the parameters.
bool SameTrellisParams(const MiningParams& a, const MiningParams& b) {
  return a.eps == b.eps && a.k_max == b.k_max && a.exclusion_frames == b.exclusion_frames &&
         a.exact == b.exact && (a.exact || SameLshFamily(a.lsh, b.lsh)) && a.seed == b.seed &&
         a.weights_path == b.weights_path && a.min_length == b.min_length;
}

// `recorded` with the options of `wanted` (resolved at `fps`) in place of its own.
MiningParams WithOptions(MiningParams recorded, const motifmine::MineOptions& wanted, double fps) {
  recorded.eps = static_cast<float>(wanted.eps);
  recorded.k_max = wanted.k_max;
  recorded.exclusion_frames = wanted.exclusion_frames;
  recorded.exact = wanted.search == "exact";
  recorded.lsh = LshOptions{};
  if (Result<LshOptions> lsh = LshOptionsFor(wanted); lsh.ok() && !recorded.exact) {
    recorded.lsh = *lsh;
    recorded.lsh.threads = 0;
  }
  recorded.seed = wanted.seed;
  recorded.weights_path = wanted.weights_path;
  recorded.branch = wanted.branch;
  recorded.min_length = ResolvedMinLengthFrames(wanted, fps);
  recorded.groups = wanted.groups;
  recorded.max_ncut = wanted.max_ncut;
  recorded.min_similarity = wanted.min_similarity;
  recorded.max_length_ratio = wanted.max_length_ratio;
  recorded.similarity = wanted.similarity;
  recorded.pause_speed = wanted.pause_speed;
  recorded.pause_seconds = wanted.pause_seconds;
  return recorded;
}

// A rule given on the command line that the recorded eps was not estimated by (an explicit eps
// overrides the rule, as in mine).
bool EpsRuleChanged(const std::set<std::string>& given, const motifmine::MineOptions& wanted,
                    const MiningParams& recorded) {
  if (!Given(given, "eps-rule") && !Given(given, "eps-angle")) return false;
  if (Given(given, "eps") && wanted.eps > 0) return false;
  if (!recorded.eps_estimated || recorded.eps_rule != wanted.eps_rule) return true;
  return wanted.eps_rule == "joint-angle" && recorded.eps_angle_degrees != wanted.eps_angle_degrees;
}

// Whether the trellis must be built again: a parameter of it given and changed.
bool TrellisChanged(const std::set<std::string>& given, const motifmine::MineOptions& wanted,
                    const MiningParams& recorded, const MiningParams& want) {
  if (Given(given, "eps") && (wanted.eps == 0 || static_cast<float>(wanted.eps) != recorded.eps)) {
    return true;
  }
  if (EpsRuleChanged(given, wanted, recorded)) return true;
  if (Given(given, "search") && wanted.search == "auto") return true;
  return !SameTrellisParams(want, recorded);
}

// The kind of build after the first, when no trellis parameter changed: the archive must extend
// the version the manifest names (same file, that commit intact).
void ChooseKind(const ReindexManifest& current, const FrameFileReader& archive,
                const std::string& archive_path, const MiningParams& want, ReindexPlan* plan) {
  Result<std::unique_ptr<FrameFileReader>> pinned = FrameFileReader::OpenCommit(
      archive_path, current.archive.generation, current.archive.committed_bytes);
  if (!pinned.ok() || (*pinned)->summary().identity != current.archive.identity) {
    plan->kind = "full";
    plan->why = "the archive is not an extension of the one version " +
                std::to_string(current.version) + " was mined from" +
                (pinned.ok() ? std::string() : " (" + pinned.status().message() + ")");
  } else if (archive.summary().identity != current.archive.identity) {
    plan->kind = "incremental";
  } else if (!(want == current.params)) {
    plan->kind = "regrow";
  }
}

// The stages of each kind; the previous version's files for an update or a regrow.
StagePlan StagesFor(const std::string& kind, const ReindexManifest* current,
                    const std::string& out_dir) {
  StagePlan stages;
  stages.archive = ArchiveStep::kGiven;
  stages.lock_folder = false;  // the reindex holds OUTDIR's lock
  stages.run_record = false;   // the manifest records the version
  stages.score = false;
  stages.save_search_cache = kind != "regrow";
  if (current != nullptr) {
    stages.previous_trellis = (fs::path(out_dir) / current->trellis.path).string();
    stages.previous_cache = (fs::path(out_dir) / current->dir / kSearchCacheFileName).string();
  }
  if (kind == "incremental") stages.trellis = TrellisStep::kUpdate;
  if (kind == "regrow") stages.trellis = TrellisStep::kLink;
  return stages;
}

}  // namespace

motifmine::MineOptions RecordedOptions(const MiningParams& params,
                                       const motifmine::MineOptions& base) {
  motifmine::MineOptions options = base;
  options.eps = params.eps;
  if (!params.eps_rule.empty()) options.eps_rule = params.eps_rule;
  if (params.eps_angle_degrees > 0) options.eps_angle_degrees = params.eps_angle_degrees;
  options.k_max = params.k_max;
  options.exclusion_frames = params.exclusion_frames;
  options.search = params.exact ? "exact" : "lsh";
  const LshOptions& lsh = params.exact ? LshOptions{} : params.lsh;
  options.lsh_tables = lsh.tables;
  options.lsh_hashes = lsh.hashes_per_table;
  options.lsh_width = lsh.bucket_width;
  options.lsh_width_per_hash = lsh.width_per_hash;
  options.lsh_probes = lsh.probes_per_table;
  options.lsh_max_candidates = lsh.max_candidates;
  options.lsh_ranking = LshRankingName(lsh.ranking);
  options.lsh_max_entries = lsh.max_entries;
  options.lsh_chain_columns = lsh.chain_columns;
  options.lsh_chained_max_candidates = lsh.chained_max_candidates;
  options.lsh_chain_probe_every = lsh.chain_probe_every;
  options.lsh_chain_sweeps = lsh.chain_sweeps;
  options.seed = params.seed;
  options.weights_path = params.weights_path;
  options.branch = params.branch;
  options.min_length_frames = params.min_length;
  options.groups = params.groups;
  options.max_ncut = params.max_ncut;
  options.min_similarity = params.min_similarity;
  options.max_length_ratio = params.max_length_ratio;
  options.similarity = params.similarity;
  options.pause_speed = params.pause_speed;
  options.pause_seconds = params.pause_seconds;
  return options;
}

ReindexPlan PlanNextVersion(const motifmine::MineOptions& options,
                            const std::set<std::string>& given, const ReindexManifest* current,
                            const FrameFileReader& archive, const std::string& archive_path,
                            const std::string& out_dir) {
  ReindexPlan plan;
  plan.options = current ? RecordedOptions(current->params, options) : options;
  for (const std::string& name : given) {
    // Both sides are the option table's own: the copy cannot fail.
    (void)SetOptionFromText(&plan.options, name, OptionAsText(options, name));
  }
  plan.eps_given = Given(given, "eps") && plan.options.eps > 0;
  if (current == nullptr) {
    plan.kind = "full";
  } else {
    const MiningParams want = WithOptions(current->params, plan.options, archive.fps());
    if (TrellisChanged(given, plan.options, current->params, want)) {
      plan.kind = "full";
      const bool rule_changed = EpsRuleChanged(given, plan.options, current->params);
      plan.why = rule_changed ? "eps is estimated again, by the rule " + plan.options.eps_rule
                              : "a parameter of the trellis changed";
      if (rule_changed) plan.options.eps = 0;  // no explicit eps: EpsRuleChanged
    } else {
      ChooseKind(*current, archive, archive_path, want, &plan);
    }
  }
  plan.stages = StagesFor(plan.kind, current, out_dir);
  return plan;
}

MiningParams RecordedParams(const ReindexPlan& plan, const ReindexManifest* current,
                            const MinePipelineResult& result, double fps) {
  MiningParams params = WithOptions(current ? current->params : MiningParams{}, plan.options, fps);
  if (!current) params.block_columns = TrellisOptions{}.block_columns;
  if (plan.kind != "full") return params;  // the trellis is the recorded one
  const TrellisReport& trellis = result.trellis;
  params.eps = trellis.params.eps;
  if (plan.options.eps == 0) {  // estimated, by the rule
    params.eps_estimated = true;
    params.mu = trellis.params.mu;
    params.sigma = trellis.params.sigma;
    params.eps_rule = plan.options.eps_rule;
    params.eps_angle_degrees =
        plan.options.eps_rule == "joint-angle" ? plan.options.eps_angle_degrees : 0.0;
  } else if (plan.eps_given || !current) {
    params.eps_estimated = false;  // given: nothing was estimated
    params.mu = 0;
    params.sigma = 0;
    params.eps_rule.clear();
    params.eps_angle_degrees = 0;
  }
  params.exclusion_frames = trellis.params.exclusion_frames;
  params.exact = trellis.search == TrellisSearchMode::kExact;
  params.lsh = params.exact ? LshOptions{} : trellis.lsh_resolved;
  params.lsh.threads = 0;
  params.weights_hash = trellis.params.weights_hash;
  return params;
}

}  // namespace motif
