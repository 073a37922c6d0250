// motifmine trellis ARCHIVE [...]: builds (or reuses, or resumes) the matching trellis, or
// audits it against exact eps-NN with --audit.
#include <cstdio>

#include "engine/cli/cli_common.h"
#include "engine/trellis/trellis_audit.h"
#include "engine/trellis/trellis_builder.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

int RunAudit(const po::variables_map& vm, const std::string& archive, const std::string& trellis,
             const LshOptions& lsh, ProgressReporter* progress) {
  AuditOptions options;
  options.sample_columns = vm["sample"].as<uint64_t>();
  options.seed = vm["seed"].as<uint64_t>();
  options.threads = vm["threads"].as<int>();
  options.weights_path = vm["weights"].as<std::string>();
  options.lsh = lsh;
  bool started = false;
  options.progress = [&](uint64_t done, uint64_t total) {
    if (!started) progress->BeginStage("audit", total, "columns");
    started = true;
    progress->Update(done);
  };
  Result<AuditReport> report = AuditTrellis(archive, trellis, options);
  if (started) progress->EndStage();
  if (!report.ok()) return ReportError("trellis", report.status());
  std::printf("audit of %s (%s)\n", trellis.c_str(), report->search_params.c_str());
  std::printf("  sampled columns       %s\n", WithCommas(report->sampled_columns).c_str());
  std::printf("  recall                %.4f  (%s of %s exact entries after the k_max cap)\n",
              report->recall, WithCommas(report->found_entries).c_str(),
              WithCommas(report->exact_entries).c_str());
  std::printf("  column recall         mean %.4f, min %.4f\n", report->mean_column_recall,
              report->min_column_recall);
  std::printf("  exact columns capped  %s (more than k_max within eps)\n",
              WithCommas(report->capped_exact_columns).c_str());
  auto share = [](uint64_t part, uint64_t whole) {
    return whole ? static_cast<double>(part) / static_cast<double>(whole) : 1.0;
  };
  std::printf("  recall, uncapped      %.4f  (%s of %s: every frame within eps)\n",
              share(report->uncapped_found_entries, report->uncapped_exact_entries),
              WithCommas(report->uncapped_found_entries).c_str(),
              WithCommas(report->uncapped_exact_entries).c_str());
  std::printf(
      "  recall, capped        %.4f  (%s of %s: the k_max nearest; %s of %s trellis "
      "columns full, with k_max verified frames within eps)\n",
      share(report->capped_found_entries, report->capped_exact_entries),
      WithCommas(report->capped_found_entries).c_str(),
      WithCommas(report->capped_exact_entries).c_str(),
      WithCommas(report->capped_columns_full).c_str(),
      WithCommas(report->capped_exact_columns).c_str());
  std::printf("  distance evaluations  %.0f per query (exact: %.0f)",
              report->lsh_evaluations_per_query, report->exact_evaluations_per_query);
  if (report->lsh_timed_columns > 0) {
    std::printf("  [LSH: over the %s columns of the chains of 16 sampled columns]",
                WithCommas(report->lsh_timed_columns).c_str());
  }
  std::printf("\n");
  if (report->lsh_seconds_per_query > 0) {
    std::printf("  time per query        %.3f ms (exact: %.3f ms, %.1fx)\n",
                1e3 * report->lsh_seconds_per_query, 1e3 * report->exact_seconds_per_query,
                report->exact_seconds_per_query / report->lsh_seconds_per_query);
  }
  return kExitOk;
}

}  // namespace

int RunTrellis(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "trellis";
  spec.usage =
      "motifmine trellis ARCHIVE [--eps X|auto] [--kmax K] [--exclusion F] "
      "[--search auto|lsh|exact] [--threads T] [--seed S] | --audit [--sample Q]";
  spec.summary =
      "Builds the matching trellis of ARCHIVE beside it (ARCHIVE.mtr): for every frame, the\n"
      "frames whose weighted pose distance is at most eps (at most K_max, the nearest), found\n"
      "with LSH (by exact brute force on archives below " +
      std::to_string(kAutoExactMaxFrames) +
      " frames, where it is faster),\n"
      "and written to disk block by block. A finished trellis with the same parameters is\n"
      "reused; an interrupted build resumes. --audit compares the trellis with exact eps-NN on\n"
      "sampled columns and prints the recall.";
  LshOptions lsh_defaults;
  spec.options.add_options()("eps", po::value<std::string>()->default_value("auto"),
                             "neighbour radius: a number, or auto (chosen by --eps-rule)")(
      "kmax", po::value<uint32_t>()->default_value(TrellisOptions{}.k_max),
      "at most this many neighbours a column")(
      "exclusion", po::value<uint32_t>()->default_value(0),
      "frames of the same clip closer than this are never neighbours (0: half of --min-length)")(
      "min-length", po::value<double>()->default_value(0.5),
      "minimum motif length in seconds (its half is the default exclusion radius)")(
      "search", po::value<std::string>()->default_value("auto"),
      ("how columns are found: lsh, exact (blocked brute force, O(N^2)), or auto (exact below " +
       std::to_string(kAutoExactMaxFrames) + " frames, lsh from there on)")
          .c_str())("exact", "the same as --search exact")(
      "threads", po::value<int>()->default_value(0), "threads (0: all cores)")(
      "seed", po::value<uint64_t>()->default_value(1), "seed of the eps sample and the LSH tables")(
      "weights", po::value<std::string>()->default_value(""),
      "per-joint weights file (\"joint weight\" lines) overriding the defaults")(
      "out", po::value<std::string>()->default_value(""), "trellis path (default ARCHIVE.mtr)")(
      "tables", po::value<uint32_t>()->default_value(lsh_defaults.tables), "LSH hash tables")(
      "hashes", po::value<uint32_t>()->default_value(lsh_defaults.hashes_per_table),
      "LSH projections per table")("width", po::value<float>()->default_value(0),
                                   "LSH bucket width (0: from the data)")(
      "probes", po::value<uint32_t>()->default_value(lsh_defaults.probes_per_table),
      "LSH buckets visited per table (multi-probe)")(
      "width-per-hash", po::value<float>()->default_value(lsh_defaults.width_per_hash),
      "LSH cell width per projection, relative to the measured neighbour distance (the width "
      "is this x projections per table x the 90th percentile of a column's neighbours' "
      "embedding distance)")("max-candidates",
                             po::value<uint32_t>()->default_value(lsh_defaults.max_candidates),
                             "LSH: at most this many exact distance evaluations a column")(
      "chain", po::value<uint32_t>()->default_value(lsh_defaults.chain_columns),
      "LSH: columns searched as chains of this many, each seeded with its predecessor's "
      "neighbours (0: every column alone)")(
      "chained-max-candidates",
      po::value<uint32_t>()->default_value(lsh_defaults.chained_max_candidates),
      "LSH: evaluations a probing chained column spends on the probed buckets after its seeds")(
      "chain-probe-every", po::value<uint32_t>()->default_value(lsh_defaults.chain_probe_every),
      "LSH: only every this-many-th column of a chain probes the buckets (with "
      "--chained-max-candidates); the columns between keep their seeds and what the chain "
      "sweeps carry over (1: every column probes)")(
      "chain-sweeps", po::value<uint32_t>()->default_value(lsh_defaults.chain_sweeps),
      "LSH: passes over each finished chain, backward then forward, in which every column "
      "verifies its neighbour column's neighbours moved by up to 2 frames (0: none)")(
      "ranking", po::value<std::string>()->default_value("sort"),
      "LSH candidate order: sort (fastest) or code (ranks gathered entries by position code: "
      "better recall on low-contrast archives, ~1.5-2.5x the time)")(
      "max-entries", po::value<uint32_t>()->default_value(lsh_defaults.max_entries),
      "LSH, --ranking code: bucket entries gathered and ranked per column")(
      "audit", "compare the existing trellis with exact eps-NN on sampled columns")(
      "sample", po::value<uint64_t>()->default_value(1000), "columns sampled by --audit");
  AddEpsilonRuleOptions(spec);
  AddProgressOptions(spec);
  spec.positional = {{"archive", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  const std::string archive = vm["archive"].as<std::string>();
  std::string trellis = vm["out"].as<std::string>();
  if (trellis.empty()) trellis = DefaultTrellisPath(archive);
  ProgressReporter progress(ProgressModeFrom(vm));

  LshOptions lsh;
  lsh.tables = vm["tables"].as<uint32_t>();
  lsh.hashes_per_table = vm["hashes"].as<uint32_t>();
  lsh.bucket_width = vm["width"].as<float>();
  lsh.probes_per_table = vm["probes"].as<uint32_t>();
  lsh.width_per_hash = vm["width-per-hash"].as<float>();
  lsh.max_candidates = vm["max-candidates"].as<uint32_t>();
  lsh.max_entries = vm["max-entries"].as<uint32_t>();
  lsh.chain_columns = vm["chain"].as<uint32_t>();
  lsh.chained_max_candidates = vm["chained-max-candidates"].as<uint32_t>();
  lsh.chain_probe_every = vm["chain-probe-every"].as<uint32_t>();
  lsh.chain_sweeps = vm["chain-sweeps"].as<uint32_t>();
  if (!ParseLshRanking(vm["ranking"].as<std::string>(), &lsh.ranking)) {
    return ReportError("trellis", Status::InvalidArgument("--ranking must be sort or code, not '" +
                                                          vm["ranking"].as<std::string>() + "'"));
  }
  if (vm.count("audit")) return RunAudit(vm, archive, trellis, lsh, &progress);

  TrellisOptions options;
  const std::string eps = vm["eps"].as<std::string>();
  if (eps != "auto") {
    char* end = nullptr;
    options.eps = std::strtof(eps.c_str(), &end);
    if (end == eps.c_str() || *end != '\0' || !(options.eps > 0)) {
      return ReportError("trellis", Status::InvalidArgument("--eps must be a positive number or "
                                                            "auto, not '" +
                                                            eps + "'"));
    }
  }
  if (Status status = EpsilonRuleFrom(vm, &options); !status.ok()) {
    return ReportError("trellis", status);
  }
  options.k_max = vm["kmax"].as<uint32_t>();
  options.exclusion_frames = vm["exclusion"].as<uint32_t>();
  options.min_length_seconds = vm["min-length"].as<double>();
  Result<TrellisSearchMode> search = ParseTrellisSearchMode(vm["search"].as<std::string>());
  options.exact = vm.count("exact") > 0;
  if (!search.ok() || (options.exact && *search == TrellisSearchMode::kLsh)) {
    std::fprintf(stderr, "motifmine trellis: %s\nusage: %s\n",
                 search.ok() ? "--exact and --search lsh contradict each other"
                             : search.status().message().c_str(),
                 spec.usage.c_str());
    return kExitUsage;
  }
  options.search = *search;
  options.threads = vm["threads"].as<int>();
  options.seed = vm["seed"].as<uint64_t>();
  options.weights_path = vm["weights"].as<std::string>();
  options.lsh = lsh;
  std::string stage;
  // Each stage reports (0 or its resume point, total) first and (total, total) last.
  options.progress = [&](const std::string& name, uint64_t done, uint64_t total) {
    if (name != stage) {
      if (!stage.empty()) progress.EndStage();
      stage = name;
      progress.BeginStage(name, total, name == "trellis" ? "columns" : "frames");
    }
    progress.Update(done);
    if (done == total) {
      progress.EndStage();
      stage.clear();
    }
  };
  options.note = [&](const std::string& message) { progress.Note(message); };
  Result<TrellisReport> report = BuildTrellis(archive, trellis, options);
  if (!stage.empty()) progress.EndStage();
  if (!report.ok()) return ReportError("trellis", report.status());
  const TrellisParams& params = report->params;
  if (report->reused) {
    std::printf("%s is up to date (same archive and parameters): reused\n", trellis.c_str());
  } else {
    std::printf("wrote %s\n", trellis.c_str());
  }
  std::printf("  eps          %.4f  (%s; the paper's mu - 2 sigma: %.4f)\n", params.eps,
              report->eps_how.c_str(), report->paper_eps);
  std::printf("  columns      %s, %s entries, mean K %.1f (k_max %u)\n",
              WithCommas(report->columns).c_str(), WithCommas(report->neighbours).c_str(),
              report->mean_k, params.k_max);
  std::printf("  exclusion    %u frames of the same clip\n", params.exclusion_frames);
  std::printf("  search       %s\n", params.search_params.c_str());
  if (!report->reused) {
    std::printf("  capped       %s columns had more than k_max neighbours within eps\n",
                WithCommas(report->capped_columns).c_str());
    std::printf("  evaluations  %.0f exact distances per column\n",
                report->columns
                    ? static_cast<double>(report->distance_evaluations) /
                          std::max<uint64_t>(1, report->columns - report->resumed_from_column)
                    : 0.0);
    std::printf(
        "  time         features %.1fs, eps %.1fs, index %.1fs, columns %.1fs (writes "
        "%.1fs beside the search, %.1fs waited for)\n",
        report->features_seconds, report->eps_seconds, report->index_seconds,
        report->search_seconds, report->write_seconds, report->write_wait_seconds);
  }
  return kExitOk;
}

}  // namespace motif::cli
