// refine_experiment: offline study of trellis refinements (docs/design/lsh.md section 8): reads an
// archive and its LSH trellis, computes exact columns of sampled columns, and measures the recall
// of refinements applied to the stored columns, with the exact evaluations they cost:
//   back      within aligned chains, each column verifies its successor's neighbours moved back
//             by 0..2 frames (the forward chaining's mirror)
//   sym       column t verifies every u whose column holds t (D is symmetric)
//   nnd r     column t verifies the columns of its r nearest neighbours (NN-descent)
// key=value arguments: archive= trellis= sample=500 seed=1 chain=64 advance=2 r=4 passes=...
// (passes: b/f backward/forward sweeps in chains of `chain`, B/F over the whole archive as one
// chain, s symmetry, n NN-descent; e.g. passes=bfbsn).
// variants=SPEC,SPEC,... instead times LshSearch variants in this process (one thread) on the
// columns [first, first + count) and measures recall on every 16th of them: SPEC letters
// s<sweeps> c<chained budget> m<max candidates> h<chain columns> p<probes> t<tables>
// w<width per hash> r<0 sort / 1 code ranking>, e.g. variants=s0,h256s4p8w0.04.
// Not a test; built beside lsh_test (docs/design/lsh.md section 3b).
#include <tbb/parallel_for.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "bench/studies/experiment_args.h"
#include "engine/distance/exact_search.h"
#include "engine/distance/pose_features.h"
#include "engine/lsh/lsh_search.h"
#include "engine/lsh/query_distance.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/trellis_file/trellis_file_reader.h"

using namespace motif;

namespace {

// A study tool: a failure ends the run with its status, never with figures computed after it.
[[noreturn]] void Die(const Status& status) {
  std::fprintf(stderr, "refine_experiment: %s\n", status.ToString().c_str());
  std::exit(1);
}

void CheckOk(const Status& status) {
  if (!status.ok()) Die(status);
}

using Columns = std::vector<std::vector<Neighbour>>;

struct Context {
  const PoseFeatures* features;
  NeighbourRules rules;
};

bool Nearer(const Neighbour& a, const Neighbour& b) {
  return a.distance < b.distance || (a.distance == b.distance && a.frame < b.frame);
}

// Verifies candidates for column t, merges the ones within eps into *column (k_max nearest,
// sorted by frame). Returns evaluations.
uint64_t Merge(const Context& context, uint64_t t, const std::vector<uint32_t>& candidates,
               std::vector<Neighbour>* column, QueryDistance* distance) {
  const PoseFeatures& features = *context.features;
  const NeighbourRules& rules = context.rules;
  std::set<uint32_t> present;
  for (const Neighbour& n : *column) present.insert(n.frame);
  distance->SetQuery(t);
  uint64_t evaluations = 0;
  const uint32_t clip_t = features.ClipOf(t);
  float bound = rules.eps;
  if (column->size() >= rules.k_max) {
    float worst = 0;
    for (const Neighbour& n : *column) worst = std::max(worst, n.distance);
    bound = std::min(bound, worst);
  }
  for (uint32_t frame : candidates) {
    if (frame >= features.frame_count()) continue;
    if (rules.Excluded(t, frame, clip_t, features.ClipOf(frame))) continue;
    if (!present.insert(frame).second) continue;
    ++evaluations;
    const float d = distance->To(frame);
    if (d <= bound) column->push_back({frame, d});
  }
  if (column->size() > rules.k_max) {
    std::nth_element(column->begin(), column->begin() + rules.k_max, column->end(), Nearer);
    column->resize(rules.k_max);
  }
  std::sort(column->begin(), column->end(),
            [](const Neighbour& a, const Neighbour& b) { return a.frame < b.frame; });
  return evaluations;
}

// Exact distances for stored columns (the file keeps quantised ones).
void Redistance(const Context& context, Columns* columns) {
  tbb::parallel_for(size_t{0}, columns->size(), [&](size_t t) {
    for (Neighbour& n : (*columns)[t]) n.distance = PoseDistance(*context.features, t, n.frame);
  });
}

// Chains: forward (successor seeds from predecessor, moved +0..advance) or backward.
uint64_t Propagate(const Context& context, Columns* columns, uint64_t chain, uint32_t advance,
                   bool forward) {
  const uint64_t n = columns->size();
  std::vector<uint64_t> evals((n + chain - 1) / chain, 0);
  tbb::parallel_for(uint64_t{0}, (n + chain - 1) / chain, [&](uint64_t c) {
    QueryDistance distance(*context.features);
    const uint64_t first = c * chain;
    const uint64_t end = std::min(n, first + chain);
    std::vector<uint32_t> candidates;
    auto step = [&](uint64_t t, uint64_t from, int sign) {
      candidates.clear();
      for (const Neighbour& nb : (*columns)[from]) {
        for (uint32_t a = 0; a <= advance; ++a) {
          const int64_t f = static_cast<int64_t>(nb.frame) + sign * static_cast<int64_t>(a);
          if (f >= 0) candidates.push_back(static_cast<uint32_t>(f));
        }
      }
      evals[c] += Merge(context, t, candidates, &(*columns)[t], &distance);
    };
    if (forward) {
      for (uint64_t t = first + 1; t < end; ++t) step(t, t - 1, +1);
    } else {
      for (uint64_t t = end - 1; t-- > first;) step(t, t + 1, -1);
    }
  });
  uint64_t total = 0;
  for (uint64_t e : evals) total += e;
  return total;
}

uint64_t Symmetric(const Context& context, Columns* columns) {
  const uint64_t n = columns->size();
  std::vector<std::vector<uint32_t>> reverse(n);
  for (uint64_t t = 0; t < n; ++t)
    for (const Neighbour& nb : (*columns)[t]) reverse[nb.frame].push_back(static_cast<uint32_t>(t));
  std::vector<uint64_t> evals(n, 0);
  tbb::parallel_for(uint64_t{0}, n, [&](uint64_t t) {
    thread_local std::unique_ptr<QueryDistance> distance;
    if (!distance) distance = std::make_unique<QueryDistance>(*context.features);
    evals[t] = Merge(context, t, reverse[t], &(*columns)[t], distance.get());
  });
  uint64_t total = 0;
  for (uint64_t e : evals) total += e;
  return total;
}

uint64_t NnDescent(const Context& context, Columns* columns, uint32_t r) {
  const uint64_t n = columns->size();
  Columns next = *columns;
  std::vector<uint64_t> evals(n, 0);
  tbb::parallel_for(uint64_t{0}, n, [&](uint64_t t) {
    thread_local std::unique_ptr<QueryDistance> distance;
    if (!distance) distance = std::make_unique<QueryDistance>(*context.features);
    std::vector<Neighbour> nearest = (*columns)[t];
    std::sort(nearest.begin(), nearest.end(), Nearer);
    if (nearest.size() > r) nearest.resize(r);
    std::vector<uint32_t> candidates;
    for (const Neighbour& nb : nearest)
      for (const Neighbour& second : (*columns)[nb.frame]) candidates.push_back(second.frame);
    evals[t] = Merge(context, t, candidates, &next[t], distance.get());
  });
  *columns = std::move(next);
  uint64_t total = 0;
  for (uint64_t e : evals) total += e;
  return total;
}

}  // namespace

int main(int argc, char** argv) {
  motif::testing::ExperimentArgs parsed(argc, argv);
  std::map<std::string, std::string>& args = parsed.values();
  auto get = [&](const std::string& key, double fallback) { return parsed.number(key, fallback); };
  auto reader = FrameFileReader::Open(args["archive"]);
  if (!reader.ok()) {
    std::printf("%s\n", reader.status().ToString().c_str());
    return 1;
  }
  // The trellis gives eps, k_max and the exclusion radius; without one (variants= only), eps= is
  // needed and k_max 256, exclusion 30 are used.
  auto trellis = TrellisFileReader::Open(args.count("trellis") ? args["trellis"] : "");
  TrellisParams params;
  if (trellis.ok()) {
    params = (*trellis)->params();
  } else if (args.count("eps") && args.count("variants")) {
    params.eps = static_cast<float>(get("eps", 0));
    params.k_max = 256;
    params.exclusion_frames = 30;
    params.seed = 1;
  } else {
    std::printf("%s\n", trellis.status().ToString().c_str());
    return 1;
  }
  auto weights = LoadDistanceWeights((*reader)->skeleton(), "");
  CheckOk(weights.status());
  auto features = PoseFeatures::FromArchive(**reader, *weights);
  CheckOk(features.status());
  Context context;
  context.features = &*features;
  context.rules.eps = params.eps;
  context.rules.k_max = params.k_max;
  context.rules.exclusion_frames = params.exclusion_frames;
  context.rules.clip_first_frames = features->clip_first_frames();
  const uint64_t n = features->frame_count();
  std::printf("%llu frames, eps %.4f, %s\n", (unsigned long long)n, params.eps,
              params.search_params.c_str());

  if (args.count("variants")) {
    // Time LshSearch variants (see the header) in this process.
    const uint64_t first = static_cast<uint64_t>(get("first", 0));
    const uint64_t count = std::min<uint64_t>(static_cast<uint64_t>(get("count", 8192)), n - first);
    std::string list = args["variants"];
    // Exact columns of every 16th column of the block, for recall.
    ExactSearch exact_block(*features, context.rules);
    std::vector<uint64_t> probe_columns;
    Columns probe_truth;
    for (uint64_t column = first; column < first + count; column += 16) {
      Columns one(1);
      SearchStats unused;
      CheckOk(exact_block.SearchColumns(column, 1, &one, &unused));
      probe_columns.push_back(column);
      probe_truth.push_back(one[0]);
    }
    size_t pos = 0;
    while (pos < list.size()) {
      size_t next = list.find(',', pos);
      if (next == std::string::npos) next = list.size();
      const std::string spec = list.substr(pos, next - pos);
      pos = next + 1;
      if (spec == "x") {  // the exact search on 256 columns of the block, one thread
        ExactSearchOptions exact_options;
        exact_options.threads = 1;
        ExactSearch exact_search(*features, context.rules, exact_options);
        Columns found;
        SearchStats stats;
        timespec t0, t1;
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t0);
        CheckOk(exact_search.SearchColumns(first, std::min<uint64_t>(256, count), &found, &stats));
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t1);
        const double cpu = (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec);
        std::printf("%-14s cpu %.1f us/column\n", "exact",
                    1e6 * cpu / std::min<uint64_t>(256, count));
        std::fflush(stdout);
        continue;
      }
      LshOptions options;
      options.seed = params.seed;
      options.threads = 1;
      for (size_t idx = 0; idx < spec.size();) {
        const char key = spec[idx++];
        size_t end = idx;
        while (end < spec.size() && (isdigit(spec[end]) || spec[end] == '.')) ++end;
        const double value = std::atof(spec.substr(idx, end - idx).c_str());
        idx = end;
        if (key == 's') options.chain_sweeps = static_cast<uint32_t>(value);
        if (key == 'c') options.chained_max_candidates = static_cast<uint32_t>(value);
        if (key == 'm') options.max_candidates = static_cast<uint32_t>(value);
        if (key == 'h') options.chain_columns = static_cast<uint32_t>(value);
        if (key == 'p') options.probes_per_table = static_cast<uint32_t>(value);
        if (key == 't') options.tables = static_cast<uint32_t>(value);
        if (key == 'w') options.width_per_hash = static_cast<float>(value);
        if (key == 'r')
          options.ranking = value != 0 ? LshRanking::kPositionCode : LshRanking::kSortValue;
      }
      auto search = LshSearch::Create(*features, context.rules, options);
      if (!search.ok()) {
        std::printf("%s\n", search.status().ToString().c_str());
        return 1;
      }
      Columns found;
      SearchStats stats;
      LshQueryStats lsh;
      timespec t0, t1;
      clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t0);
      CheckOk((*search)->SearchColumns(first, count, &found, &stats, &lsh));
      clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t1);
      const double cpu = (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec);
      uint64_t hits = 0, total = 0;
      for (size_t idx = 0; idx < probe_columns.size(); ++idx) {
        std::set<uint32_t> have;
        for (const Neighbour& nb : found[probe_columns[idx] - first]) have.insert(nb.frame);
        for (const Neighbour& nb : probe_truth[idx]) hits += have.count(nb.frame);
        total += probe_truth[idx].size();
      }
      std::printf("%-14s recall %.4f  ", spec.c_str(), total ? double(hits) / total : 1.0);
      std::printf(
          "cpu %.1f us/column, evaluations %.0f (seeds %.0f, sweeps %.0f), entries "
          "%.0f, probes %.1f, extensions %.2f, budget-capped %.2f\n",
          1e6 * cpu / count, double(stats.distance_evaluations) / count,
          double(lsh.seed_evaluations) / count, double(lsh.sweep_evaluations) / count,
          double(lsh.entries_examined) / count, double(lsh.probes) / count,
          double(lsh.extensions) / count, double(lsh.columns_budget_capped) / count);
      std::fflush(stdout);
    }
    return 0;
  }

  Columns columns;
  CheckOk((*trellis)->ReadColumns(0, n, &columns));
  Redistance(context, &columns);

  const uint64_t sample_count = static_cast<uint64_t>(get("sample", 500));
  std::mt19937_64 rng(static_cast<uint64_t>(get("seed", 1)));
  std::set<uint64_t> chosen;
  while (chosen.size() < std::min(sample_count, n)) chosen.insert(rng() % n);
  std::vector<uint64_t> sample(chosen.begin(), chosen.end());
  ExactSearch exact(*features, context.rules);
  Columns truth(sample.size());
  std::vector<bool> capped(sample.size());
  for (size_t idx = 0; idx < sample.size(); ++idx) {
    Columns one(1);
    SearchStats stats;
    CheckOk(exact.SearchColumns(sample[idx], 1, &one, &stats));
    truth[idx] = one[0];
    capped[idx] = stats.capped_columns > 0;
  }
  auto recall = [&](const Columns& cols, const char* what, uint64_t evaluations) {
    uint64_t hits = 0, total = 0, hits_c = 0, total_c = 0;
    for (size_t idx = 0; idx < sample.size(); ++idx) {
      std::set<uint32_t> have;
      for (const Neighbour& nb : cols[sample[idx]]) have.insert(nb.frame);
      for (const Neighbour& nb : truth[idx]) {
        const bool hit = have.count(nb.frame) > 0;
        hits += hit;
        ++total;
        if (capped[idx]) {
          hits_c += hit;
          ++total_c;
        }
      }
    }
    std::printf("%-40s recall %.4f (capped %.4f, uncapped %.4f)  +%.0f evaluations/column\n", what,
                total ? double(hits) / total : 1.0, total_c ? double(hits_c) / total_c : 1.0,
                total > total_c ? double(hits - hits_c) / (total - total_c) : 1.0,
                double(evaluations) / n);
    std::fflush(stdout);
  };
  recall(columns, "stored", 0);
  const uint64_t chain = static_cast<uint64_t>(get("chain", 64));
  const uint32_t advance = static_cast<uint32_t>(get("advance", 2));
  const std::string passes = args.count("passes") ? args["passes"] : "b,s,f,b,n";
  const uint32_t r = static_cast<uint32_t>(get("r", 4));
  uint64_t total = 0;
  std::string done;
  for (char pass : passes) {
    if (pass == ',') continue;
    uint64_t e = 0;
    if (pass == 'b') e = Propagate(context, &columns, chain, advance, false);
    if (pass == 'f') e = Propagate(context, &columns, chain, advance, true);
    if (pass == 'B') e = Propagate(context, &columns, n, advance, false);  // one chain
    if (pass == 'F') e = Propagate(context, &columns, n, advance, true);
    if (pass == 's') e = Symmetric(context, &columns);
    if (pass == 'n') e = NnDescent(context, &columns, r);
    total += e;
    done += pass;
    recall(columns, ("after " + done).c_str(), total);
  }
  return 0;
}
