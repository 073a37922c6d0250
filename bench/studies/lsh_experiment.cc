// lsh_experiment: the study tool behind docs/design/lsh.md (not a test; built with the tests, as
// it uses their helpers: bench/studies/CMakeLists.txt).
// key=value arguments:
//   data=real|synth|synthbig|reseq frames=N seed=S queries=Q k_max=K eps=E
//   LSH options: tables= hashes= width= width_per_hash= probes= max_candidates= max_bucket_scan=
//                first_round= stages= sparse= chain= chain_advance= chained= probe_every=
//                sweeps=
//                ranking=sort|code
//                max_entries= threads=
//                range=(columns timed in one block)
//   modes: oracle (how well L2 / l1,2 embedding distances rank the exact neighbours),
//          contrast (D_2k/D_k, D_4k/D_k, D_16k/D_k), simulate bits=B (offline ranking of all
//          probed entries by their projected distance), diagnose [count] (misses in probed
//          buckets), worst (columns under 0.5 recall), exact_speed exact_columns=C.
// Ground truth (the direct loop with PoseDistance) is cached in /tmp/lshgt_*.bin.
#include <tbb/parallel_for.h>

#include <malloc.h>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <map>
#include <set>

#include "bench/studies/experiment_args.h"
#include "engine/distance/exact_search.h"
#include "engine/lsh/lsh_search.h"
#include "engine/lsh/lsh_tuning.h"
#include "tests/engine/lsh/lsh_test_util.h"
#include "tests/testing/mocap_data.h"

using namespace motif;
using namespace motif::testing;

namespace {

// A study tool: a failure ends the run with its status, never with figures computed after it.
[[noreturn]] void Die(const Status& status) {
  std::fprintf(stderr, "lsh_experiment: %s\n", status.ToString().c_str());
  std::exit(1);
}

void CheckOk(const Status& status) {
  if (!status.ok()) Die(status);
}

template <typename T>
T ValueOrDie(Result<T> result) {
  if (!result.ok()) Die(result.status());
  return std::move(result).value();
}

}  // namespace

int main(int argc, char** argv) {
  motif::testing::ExperimentArgs parsed(argc, argv);
  std::map<std::string, std::string>& args = parsed.values();
  auto get = [&](const std::string& key, double fallback) { return parsed.number(key, fallback); };
  const std::string data = args.count("data") ? args["data"] : "synth";
  const uint64_t frames = static_cast<uint64_t>(get("frames", 40000));
  const uint32_t queries = static_cast<uint32_t>(get("queries", 400));
  auto t0 = std::chrono::steady_clock::now();
  PoseFeatures features;
  if (data == "real") {
    auto loaded = RealTakeFeatures(MocapDir() + "/bvh");
    if (!loaded.ok()) {
      std::printf("%s\n", loaded.status().ToString().c_str());
      return 1;
    }
    features = std::move(*loaded);
  } else if (data == "synthbig") {
    SynthOptions so;
    so.frames = frames;
    so.seed = static_cast<uint64_t>(get("seed", 7));
    auto synthesizer = MotionSynthesizer::Create(so);
    CheckOk(synthesizer.status());
    const Skeleton& skeleton = (*synthesizer)->skeleton();
    const FrameLayout layout{static_cast<uint32_t>(skeleton.joint_count())};
    std::vector<float> rows;
    rows.reserve(frames * layout.stride());
    std::vector<uint64_t> starts;
    CheckOk((*synthesizer)->Run([&](const ClipFrames& clip) {
      starts.push_back(rows.size() / layout.stride());
      rows.insert(rows.end(), clip.rows.begin(), clip.rows.end());
      return Status::Ok();
    }));
    features = PoseFeatures::FromRows(rows.data(), rows.size() / layout.stride(),
                                      layout.joint_count, DefaultWeights(skeleton), starts);
    rows = std::vector<float>();
  } else if (data == "reseq") {
    auto sources = DiscoverTakes({MocapDir() + "/bvh"}, ImportOptions());
    CheckOk(sources.status());
    std::vector<Take> takes;
    for (const TakeSource& source : *sources) {
      Take take = ValueOrDie(ImportTake(source, ImportOptions()));
      if (!takes.empty()) CheckOk(ConformToSkeleton(takes[0].skeleton, &take));
      takes.push_back(ResampleTake(take, 120.0));
    }
    SynthOptions so;
    so.frames = frames;
    so.seed = static_cast<uint64_t>(get("seed", 7));
    auto synthesizer = MotionSynthesizer::CreateFromTakes(so, std::move(takes));
    if (!synthesizer.ok()) {
      std::printf("%s\n", synthesizer.status().ToString().c_str());
      return 1;
    }
    std::vector<ClipFrames> clips;
    CheckOk((*synthesizer)->Run([&](const ClipFrames& clip) {
      clips.push_back(clip);
      return Status::Ok();
    }));
    features = FeaturesFromClips((*synthesizer)->skeleton(), clips);
  } else {
    features = SyntheticFeatures(frames, static_cast<uint64_t>(get("seed", 7)));
  }
  auto t1 = std::chrono::steady_clock::now();
  NeighbourRules rules = RulesWithEstimatedEps(features, static_cast<uint32_t>(get("k_max", 256)));
  if (args.count("eps")) rules.eps = get("eps", 1);
  std::printf("data=%s frames=%llu clips=%zu eps=%.4f load=%.1fs\n", data.c_str(),
              (unsigned long long)features.frame_count(), features.clip_first_frames().size(),
              rules.eps, std::chrono::duration<double>(t1 - t0).count());

  std::vector<uint64_t> columns = SampleColumns(features.frame_count(), queries, 11);
  // ground truth cache
  char cache[256];
  std::snprintf(cache, sizeof(cache), "/tmp/lshgt_%s_%llu_%u_%.5f_%u.bin", data.c_str(),
                (unsigned long long)features.frame_count(), queries, rules.eps, rules.k_max);
  std::vector<std::vector<Neighbour>> exact(columns.size());
  std::vector<uint64_t> eps_counts(columns.size());
  {
    std::ifstream in(cache, std::ios::binary);
    if (in) {
      for (size_t idx = 0; idx < columns.size(); ++idx) {
        uint64_t n = 0;
        in.read(reinterpret_cast<char*>(&n), 8);
        exact[idx].resize(n);
        in.read(reinterpret_cast<char*>(exact[idx].data()), n * sizeof(Neighbour));
      }
    } else {
      auto tg = std::chrono::steady_clock::now();
      tbb::parallel_for(size_t{0}, columns.size(), [&](size_t idx) {
        exact[idx] = ExactColumn(features, rules, columns[idx]);
      });
      std::printf("exact: %.2fs\n",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - tg).count());
      std::ofstream out(cache, std::ios::binary);
      for (size_t idx = 0; idx < columns.size(); ++idx) {
        uint64_t n = exact[idx].size();
        out.write(reinterpret_cast<char*>(&n), 8);
        out.write(reinterpret_cast<const char*>(exact[idx].data()), n * sizeof(Neighbour));
      }
    }
  }
  double exact_mean = 0;
  size_t full = 0;
  for (auto& c : exact) {
    exact_mean += c.size();
    full += c.size() == rules.k_max;
  }
  std::printf("exact neighbours/column %.1f, columns at k_max %zu/%zu\n", exact_mean / exact.size(),
              full, exact.size());

  if (args.count("exact_speed")) {
    ExactSearchOptions eo;
    eo.threads = static_cast<uint32_t>(get("threads", 0));
    ExactSearch exact_search(features, rules, eo);
    const uint64_t count = static_cast<uint64_t>(get("exact_columns", 512));
    std::vector<std::vector<Neighbour>> cols;
    SearchStats st;
    auto t = std::chrono::steady_clock::now();
    Status status = exact_search.SearchColumns(features.frame_count() / 2, count, &cols, &st);
    CheckOk(status);
    double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    std::printf(
        "exact search: %s %llu columns in %.2fs = %.1f us/column wall, %.2f ns/eval wall; full "
        "archive would take %.0f s\n",
        status.ToString().c_str(), (unsigned long long)count, sec, 1e6 * sec / count,
        1e9 * sec / (count * (double)features.frame_count()), sec / count * features.frame_count());
    // sanity vs direct loop
    size_t same = 0;
    for (uint64_t i = 0; i < std::min<uint64_t>(count, 16); ++i)
      same += cols[i] == ExactColumn(features, rules, features.frame_count() / 2 + i);
    std::printf("identical to direct loop: %zu/16\n", same);
    return 0;
  }
  if (args.count("contrast")) {
    std::vector<double> r1, r2, r4, r16;
    for (size_t qi = 0; qi < std::min<size_t>(columns.size(), 100); ++qi) {
      const uint64_t q = columns[qi];
      const uint32_t qclip = features.ClipOf(q);
      std::vector<float> d;
      for (uint64_t f = 0; f < features.frame_count(); ++f) {
        if (rules.Excluded(q, f, qclip, features.ClipOf(f))) continue;
        d.push_back(PoseDistance(features, q, f));
      }
      std::sort(d.begin(), d.end());
      const size_t k = rules.k_max;
      if (d[k - 1] > rules.eps) continue;
      r1.push_back(d[k - 1]);
      r2.push_back(d[2 * k - 1] / d[k - 1]);
      r4.push_back(d[4 * k - 1] / d[k - 1]);
      r16.push_back(d[16 * k - 1] / d[k - 1]);
    }
    auto med = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v.empty() ? 0 : v[v.size() / 2];
    };
    auto p10 = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v.empty() ? 0 : v[v.size() / 10];
    };
    std::printf(
        "capped columns %zu: D_k median %.3f; D_2k/D_k median %.3f p10 %.3f; D_4k/D_k %.3f p10 "
        "%.3f; D_16k/D_k %.3f p10 %.3f\n",
        r1.size(), med(r1), med(r2), p10(r2), med(r4), p10(r4), med(r16), p10(r16));
    return 0;
  }
  if (args.count("oracle")) {
    // For each sampled column: rank of the exact neighbours under proxies; report the number of
    // proxy-nearest candidates needed to cover 90/95/99 % of the exact column (pooled quantiles).
    HashFamily family = HashFamily::Draw(features.weights(), 1, 1, 1.0f, 1);
    const uint32_t dims = family.embedding_dims();
    const uint32_t J = features.weighted_joint_count();
    std::vector<float> all((size_t)features.frame_count() * dims);
    for (uint64_t f = 0; f < features.frame_count(); ++f)
      family.Embed(features.frame(f), &all[f * dims]);
    std::vector<std::vector<double>> needed(2);  // per proxy: per exact neighbour, its proxy rank
    std::vector<std::vector<double>> share(2);
    for (size_t qi = 0; qi < columns.size(); ++qi) {
      if (exact[qi].empty()) continue;
      const uint64_t q = columns[qi];
      const uint32_t qclip = features.ClipOf(q);
      std::vector<std::pair<float, uint32_t>> l2, l12;
      for (uint64_t f = 0; f < features.frame_count(); ++f) {
        if (rules.Excluded(q, f, qclip, features.ClipOf(f))) continue;
        float sq = 0, mixed = 0;
        for (uint32_t k = 0; k < J; ++k) {
          float jk = 0;
          for (uint32_t d = 0; d < 10; ++d) {
            float diff = all[f * dims + k * 10 + d] - all[q * dims + k * 10 + d];
            jk += diff * diff;
          }
          sq += jk;
          mixed += std::sqrt(jk);
        }
        l2.push_back({sq, (uint32_t)f});
        l12.push_back({mixed, (uint32_t)f});
      }
      for (int p = 0; p < 2; ++p) {
        auto& v = p == 0 ? l2 : l12;
        std::sort(v.begin(), v.end());
        std::vector<uint32_t> rank(features.frame_count(), UINT32_MAX);
        for (size_t r = 0; r < v.size(); ++r) rank[v[r].second] = r;
        std::vector<double> ranks;
        for (auto& n : exact[qi]) ranks.push_back(rank[n.frame] + 1);
        std::sort(ranks.begin(), ranks.end());
        // candidates needed for 95% of this column
        share[p].push_back(
            ranks[std::min(ranks.size() - 1, (size_t)std::ceil(0.95 * ranks.size()) - 1)] /
            ranks.size());
        for (double r : ranks) needed[p].push_back(r / exact[qi].size());
      }
    }
    for (int p = 0; p < 2; ++p) {
      auto v = needed[p];
      std::sort(v.begin(), v.end());
      auto c = share[p];
      std::sort(c.begin(), c.end());
      std::printf(
          "%s: pooled rank/|col| quantiles 0.9=%.2f 0.95=%.2f 0.99=%.2f; per-column 95%%-cover "
          "ratio median=%.2f p90=%.2f\n",
          p == 0 ? "L2(e)" : "L1,2(e)", v[v.size() * 9 / 10], v[v.size() * 95 / 100],
          v[v.size() * 99 / 100], c[c.size() / 2], c[c.size() * 9 / 10]);
    }
    return 0;
  }
  LshOptions options;
  options.tables = static_cast<uint32_t>(get("tables", options.tables));
  options.hashes_per_table = static_cast<uint32_t>(get("hashes", options.hashes_per_table));
  options.width_per_hash = static_cast<float>(get("width_per_hash", options.width_per_hash));
  options.bucket_width = static_cast<float>(get("width", 0));
  options.probes_per_table = static_cast<uint32_t>(get("probes", options.probes_per_table));
  options.max_candidates = static_cast<uint32_t>(get("max_candidates", options.max_candidates));
  options.max_bucket_scan = static_cast<uint32_t>(get("max_bucket_scan", options.max_bucket_scan));
  options.threads = static_cast<int>(get("threads", 0));
  options.first_round_scan = static_cast<uint32_t>(get("first_round", options.first_round_scan));
  options.extension_stages = static_cast<uint32_t>(get("stages", options.extension_stages));
  options.sparse_radius_factor = static_cast<float>(get("sparse", options.sparse_radius_factor));
  if (args.count("ranking")) ParseLshRanking(args["ranking"], &options.ranking);
  options.max_entries = static_cast<uint32_t>(get("max_entries", options.max_entries));
  options.chain_columns = static_cast<uint32_t>(get("chain", options.chain_columns));
  options.chain_advance = static_cast<uint32_t>(get("chain_advance", options.chain_advance));
  options.chained_max_candidates =
      static_cast<uint32_t>(get("chained", options.chained_max_candidates));
  options.chain_probe_every = static_cast<uint32_t>(get("probe_every", options.chain_probe_every));
  options.chain_sweeps = static_cast<uint32_t>(get("sweeps", options.chain_sweeps));
  auto rss = [] {
    malloc_trim(0);
    std::ifstream status("/proc/self/status");
    std::string key;
    double kb = 0;
    while (status >> key) {
      if (key == "VmRSS:") {
        status >> kb;
        break;
      }
      std::getline(status, key);
    }
    return kb * 1024;
  };
  auto peak = [] {
    std::ifstream status("/proc/self/status");
    std::string key;
    double kb = 0;
    while (status >> key) {
      if (key == "VmHWM:") {
        status >> kb;
        break;
      }
      std::getline(status, key);
    }
    return kb * 1024;
  };
  const double rss_before = rss();
  {
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
  }
  auto tr = std::chrono::steady_clock::now();
  SearchScale scale = EstimateSearchScale(features, rules, options);
  float radius = scale.radius;
  auto tb = std::chrono::steady_clock::now();
  auto search = LshSearch::Create(features, rules, options);
  auto tc = std::chrono::steady_clock::now();
  if (!search.ok()) {
    std::printf("%s\n", search.status().ToString().c_str());
    return 1;
  }
  std::printf(
      "memory: features %.1f B/frame; rss before create %.1f B/frame; peak growth during create "
      "%.1f B/frame\n",
      (double)features.memory_bytes() / features.frame_count(), rss_before / features.frame_count(),
      (peak() - rss_before) / features.frame_count());
  std::printf("neighbour_l2 median %.4f p90 %.4f pairs %llu\n", scale.neighbour_l2,
              scale.neighbour_l2_p90, (unsigned long long)scale.neighbour_pairs);
  std::printf("%s\nradius=%.4f (%.2fs) build=%.2fs index=%.1f B/frame\n",
              (*search)->DescribeParams().c_str(), radius,
              std::chrono::duration<double>(tb - tr).count(),
              std::chrono::duration<double>(tc - tb).count(),
              (double)(*search)->index().memory_bytes() / features.frame_count());
  auto bstats = (*search)->index().BucketStats(0);
  std::printf("table0: buckets=%llu largest=%llu mean bucket per frame=%.1f\n",
              (unsigned long long)bstats.buckets, (unsigned long long)bstats.largest_bucket,
              bstats.mean_entries_per_frame_bucket);

  std::vector<std::vector<Neighbour>> approx(columns.size());
  SearchStats stats;
  LshQueryStats lsh_stats;
  auto tq = std::chrono::steady_clock::now();
  for (size_t idx = 0; idx < columns.size(); ++idx) {
    std::vector<std::vector<Neighbour>> one;
    CheckOk((*search)->SearchColumns(columns[idx], 1, &one, &stats, &lsh_stats));
    approx[idx] = one[0];
  }
  double tquery = std::chrono::duration<double>(std::chrono::steady_clock::now() - tq).count();
  if (args.count("simulate")) {
    // Offline: rank all entries of all probed buckets by a priority, verify the first B.
    const HashFamily& family = (*search)->family();
    const uint32_t m = family.hashes_per_table();
    const uint32_t rows = m + 1;
    const float w = family.bucket_width();
    std::vector<float> e(family.embedding_dims());
    std::vector<float> qproj(family.table_count() * rows), proj(family.table_count() * rows);
    const int budgets[] = {1024, 2048, 4096, 8192};
    double hits[3][4] = {};
    double total = 0, entries_total = 0;
    for (size_t qi = 0; qi < columns.size(); ++qi) {
      const uint64_t q = columns[qi];
      family.Embed(features.frame(q), e.data());
      family.Project(e.data(), qproj.data());
      auto seq = (*search)->ProbeSequence(q);
      std::map<uint32_t, std::array<float, 3>> prio;  // frame -> (codeLB, exactproj, sLB)
      const uint32_t qclip = features.ClipOf(q);
      for (auto& p : seq) {
        auto r = (*search)->index().FindBucket(p.table_idx, p.key);
        const auto& table = (*search)->index().table(p.table_idx);
        for (uint32_t pos = r.first; pos < r.second; ++pos) {
          uint32_t f = table.frames[pos];
          if (rules.Excluded(q, f, qclip, features.ClipOf(f))) continue;
          entries_total += 1;
          family.Embed(features.frame(f), e.data());
          family.Project(e.data(), proj.data());
          const float* a = &qproj[p.table_idx * rows];
          const float* b = &proj[p.table_idx * rows];
          double code = 0, exact_proj = 0;
          const int bits = static_cast<int>(get("bits", 1));
          const double levels = 1 << bits;
          for (uint32_t i = 0; i < m; ++i) {
            double d = (b[i] - a[i]) * w;
            exact_proj += d * d;
            // entry's interval at code resolution
            double cb = std::floor(b[i]);
            double k = std::floor((b[i] - cb) * levels);
            double lo = cb + k / levels, hi = cb + (k + 1) / levels;
            double gap = a[i] < lo ? lo - a[i] : (a[i] > hi ? a[i] - hi : 0.0);
            code += (gap * w) * (gap * w);
          }
          double sd = (b[m] - a[m]);
          double slb = p.lower_bound * p.lower_bound + sd * sd;
          auto it = prio.find(f);
          std::array<float, 3> v{(float)code, (float)exact_proj, (float)slb};
          if (it == prio.end())
            prio[f] = v;
          else
            for (int k = 0; k < 3; ++k) it->second[k] = std::min(it->second[k], v[k]);
        }
      }
      std::set<uint32_t> truth;
      for (auto& n : exact[qi]) truth.insert(n.frame);
      total += truth.size();
      for (int k = 0; k < 3; ++k) {
        std::vector<std::pair<float, uint32_t>> order;
        for (auto& [f, v] : prio) order.push_back({v[k], f});
        std::sort(order.begin(), order.end());
        for (int bi = 0; bi < 4; ++bi) {
          int h = 0;
          for (int r = 0; r < std::min<int>(budgets[bi], order.size()); ++r)
            h += truth.count(order[r].second);
          hits[k][bi] += h;
        }
      }
    }
    std::printf("entries per query %.0f\n", entries_total / columns.size());
    const char* names[] = {"code1bit", "exactproj", "sLB"};
    for (int k = 0; k < 3; ++k) {
      std::printf("%s:", names[k]);
      for (int bi = 0; bi < 4; ++bi) std::printf(" B=%d %.3f", budgets[bi], hits[k][bi] / total);
      std::printf("\n");
    }
    return 0;
  }
  if (args.count("diagnose")) {
    // For each missed exact neighbour: is it in any probed bucket?
    const HashFamily& family = (*search)->family();
    std::vector<float> e(family.embedding_dims());
    std::vector<float> proj(family.table_count() * (family.hashes_per_table() + 1));
    uint64_t missed = 0, missed_in_probed = 0, found = 0, total = 0, total_entries = 0;
    std::vector<double> nb_count_hist(65), all_count_hist(65);
    std::vector<uint64_t> probed_tables_hist(family.table_count() + 1);
    for (size_t qi = 0; qi < columns.size(); ++qi) {
      auto seq = (*search)->ProbeSequence(columns[qi]);
      std::set<std::pair<uint32_t, uint32_t>> probed;
      for (auto& p : seq) probed.insert({p.table_idx, p.key});
      uint64_t entries = 0;
      std::map<uint32_t, int> counts;
      for (auto& p : probed) {
        auto r = (*search)->index().FindBucket(p.first, p.second);
        entries += r.second - r.first;
        if (args.count("count"))
          for (uint32_t i = r.first; i < r.second; ++i)
            counts[(*search)->index().table(p.first).frames[i]]++;
      }
      total_entries += entries;
      if (args.count("count")) {
        // rank exact neighbours by count: how many candidates have count >= that of each neighbour
        std::vector<int> hist(65);
        for (auto& c : counts) hist[std::min(64, c.second)]++;
        for (auto& n : exact[qi]) {
          int c = counts.count(n.frame) ? counts[n.frame] : 0;
          nb_count_hist[std::min(64, c)]++;
        }
        for (int c = 0; c <= 64; ++c) all_count_hist[c] += hist[c];
      }
      for (auto& n : exact[qi]) {
        ++total;
        bool got = false;
        for (auto& a : approx[qi]) got |= a.frame == n.frame;
        family.Embed(features.frame(n.frame), e.data());
        family.Project(e.data(), proj.data());
        uint32_t hit_tables = 0;
        for (uint32_t t = 0; t < family.table_count(); ++t) {
          uint32_t key = family.KeyOfCoordinates(&proj[t * (family.hashes_per_table() + 1)]);
          hit_tables += probed.count({t, key});
        }
        probed_tables_hist[hit_tables]++;
        if (got)
          ++found;
        else {
          ++missed;
          if (hit_tables) ++missed_in_probed;
        }
      }
    }
    std::printf("diagnose: total %llu found %llu missed %llu (of which in a probed bucket %llu)\n",
                (unsigned long long)total, (unsigned long long)found, (unsigned long long)missed,
                (unsigned long long)missed_in_probed);
    std::printf("entries in probed buckets per query: %.0f\n",
                (double)total_entries / columns.size());
    if (args.count("count")) {
      double nb_total = 0, all_total = 0;
      for (int c = 64; c >= 1; --c) {
        nb_total += nb_count_hist[c];
        all_total += all_count_hist[c];
        if (nb_count_hist[c] + all_count_hist[c] > 0)
          std::printf("count>=%d: neighbours %.3f, candidates/q %.0f\n", c, nb_total / total,
                      all_total / columns.size());
      }
    }
    std::printf("tables probed-hit histogram:");
    for (auto h : probed_tables_hist) std::printf(" %llu", (unsigned long long)h);
    std::printf("\n");
  }
  RecallStats recall = Recall(exact, approx);
  if (args.count("worst")) {
    for (size_t idx = 0; idx < columns.size(); ++idx) {
      RecallStats one = Recall({exact[idx]}, {approx[idx]});
      if (one.column_mean < 0.5) {
        float far = 0;
        for (auto& n : exact[idx]) far = std::max(far, n.distance);
        std::printf("column %llu: exact %zu (max d %.3f) found %zu recall %.2f\n",
                    (unsigned long long)columns[idx], exact[idx].size(), far, approx[idx].size(),
                    one.column_mean);
      }
    }
  }
  std::printf(
      "recall pooled=%.4f column_mean=%.4f worst=%.3f | evals/q=%.0f examined/q=%.0f probes/q=%.1f "
      "budget_capped=%.3f bound_stopped=%.3f ext/q=%.2f | %.1f us/q (sampled, 1 col calls)\n",
      recall.pooled(), recall.column_mean, recall.worst_column,
      (double)stats.distance_evaluations / columns.size(),
      (double)lsh_stats.entries_examined / columns.size(),
      (double)lsh_stats.probes / columns.size(),
      (double)lsh_stats.columns_budget_capped / columns.size(),
      (double)lsh_stats.columns_bound_stopped / columns.size(),
      (double)lsh_stats.extensions / columns.size(), 1e6 * tquery / columns.size());
  // throughput on a contiguous range
  const uint64_t range = std::min<uint64_t>(features.frame_count(), (uint64_t)get("range", 20000));
  std::vector<std::vector<Neighbour>> block;
  SearchStats bstats2;
  const uint64_t block_first = (features.frame_count() - range) / 2;
  auto cpu = [] {
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
  };
  const double c0 = cpu();
  auto ts = std::chrono::steady_clock::now();
  CheckOk((*search)->SearchColumns(block_first, range, &block, &bstats2));
  double tblock = std::chrono::duration<double>(std::chrono::steady_clock::now() - ts).count();
  const double cblock = cpu() - c0;
  std::printf("peak growth after block %.1f B/frame\n",
              (peak() - rss_before) / features.frame_count());
  std::printf(
      "block of %llu columns: %.2fs = %.1f us/column wall, %.1f us/column cpu, evals/col=%.0f\n",
      (unsigned long long)range, tblock, 1e6 * tblock / range, 1e6 * cblock / range,
      (double)bstats2.distance_evaluations / range);
  return 0;
}
