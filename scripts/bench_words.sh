#!/usr/bin/env bash
# `motifmine words` scaling for docs/benchmarks.md (bench/bench_engine_words.cc): the whole job
# (pool, DTW neighbours, training, embedding every word, k-means, signatures) against the number
# of words, one fresh process per archive size so each peak resident set is its own.
#   scripts/bench_words.sh [quick|full]   quick: 2^17 and 2^19 frames; full: also 2^21, 10^7
# Raw JSON in bench-results/words-<date>/, a markdown table on stdout. Archives are written once
# to $MOTIF_BENCH_DIR/words (default /tmp/motifmine-bench/words) and kept for later runs.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode="${1:-quick}"
build="${MOTIF_BUILD_DIR:-$root/build}"
bench="$build/bench/bench_engine_words"
[ -x "$bench" ] || MOTIF_BUILD_DIR="$build" "$root/scripts/build.sh" >/dev/null
out="$root/bench-results/words-$(date +%Y%m%d-%H%M%S)"
mkdir -p "$out"
export MOTIF_BENCH_WORDS_MAX=524288
[ "$mode" = full ] && export MOTIF_BENCH_WORDS_MAX=10000000
echo "- $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), load average $(cut -d' ' -f1-3 /proc/loadavg)" | tee "$out/machine.md"
mapfile -t names < <("$bench" --benchmark_list_tests)
for name in "${names[@]}"; do
  file="$out/$(echo "$name" | tr '/:' '__').json"
  "$bench" --benchmark_filter="^${name}\$" --benchmark_out="$file" --benchmark_out_format=json \
    > /dev/null
  echo "done $name (load average $(cut -d' ' -f1-3 /proc/loadavg))" >&2
done
python3 - "$out" <<'PY' | tee "$out/table.md"
import glob, json, sys
print("| frames | words | pool words | wall s | CPU s | pool s | neighbours s | train s | embed s | k-means s | signatures s | peak RSS MB | bytes/word |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
rows = []
for path in glob.glob(sys.argv[1] + "/*.json"):
    for b in json.load(open(path))["benchmarks"]:
        if b.get("error_occurred"):
            continue
        rows.append(b)
for b in sorted(rows, key=lambda b: b["words"]):
    frames = int(b["name"].split("frames:")[1].split("/")[0])
    print(f"| {frames:,} | {b['words']:,.0f} | {b['pool_words']:,.0f} | {b['real_time']:.0f} | {b['cpu_s']:.0f} | "
          f"{b['pool_s']:.1f} | {b['neighbours_s']:.1f} | {b['train_s']:.0f} | {b['embed_s']:.1f} | "
          f"{b['kmeans_s']:.1f} | {b['signatures_s']:.2f} | {b['peak_rss_mb']:.0f} | {b['peak_rss_bytes_per_word']:,.0f} |")
PY
