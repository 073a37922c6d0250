#!/usr/bin/env bash
# Matching-trellis scaling for docs/benchmarks.md: the whole build (features, eps, index, column
# search, spill to the .mtr file) with LSH and with the exact search, against N, on the
# procedural synthetic archive and the re-sequenced real takes (bench/bench_engine_trellis.cc).
#   scripts/bench_trellis.sh [quick|full] [REGEX]
#     quick: N = 2^14 .. 2^20 (the default); full: N = 2^14 .. 2^24 (LSH, and the exact build
#     extrapolated above 2^17). REGEX (optional) keeps only the benchmarks whose name matches it.
#     (scripts/bench.sh runs the same benchmarks as its "trellis" job, one process for the
#     whole series, and makes the docs' tables and plots; this script runs one process per
#     benchmark and prints its own tables.)
#   scripts/bench_trellis.sh table DIR   prints the table of the JSON files in DIR (e.g. of a run
#     that was stopped part way).
# Every benchmark runs in a fresh process (--benchmark_filter), so its peak resident memory is
# its own. Order: the small sizes first (the exact/LSH crossover), then 2^18, 2^20 (2 threads,
# then 1), then 10^7. Raw JSON: bench-results/trellis-<date>/ (one file per benchmark), then a
# markdown table on stdout (also bench-results/trellis-<date>/table.md). Archives are written
# once to $MOTIF_BENCH_DIR/archives (default /tmp/motifmine-bench) and kept for later runs.
# MOTIF_BUILD_DIR: the build to use (default build/; built if the benchmark is missing).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode="${1:-quick}"
only="${2:-}"
build="${MOTIF_BUILD_DIR:-$root/build}"
if [ "$mode" = table ]; then
  out="${2:?table DIR}"
else
bench="$build/bench/bench_engine_trellis"
[ -x "$bench" ] || MOTIF_BUILD_DIR="$build" "$root/scripts/build.sh" >/dev/null
out="$root/bench-results/trellis-$(date +%Y%m%d-%H%M%S)"
mkdir -p "$out"
export MOTIF_BENCH_MAX_FRAMES=1048576
[ "$mode" = full ] && export MOTIF_BENCH_MAX_FRAMES=16777216

{
  echo "- $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'),"\
       "$(free -g | awk '/Mem:/{print $2}') GiB, $(uname -sr), load average $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "- $bench, mode $mode, started $(date -u +%FT%TZ)"
} > "$out/machine.md"
cat "$out/machine.md"

# Every registered benchmark, reordered by size (then 2 threads before 1).
mapfile -t names < <("$bench" --benchmark_list_tests | grep -E "${only:-.}" | python3 -c '
import re, sys
names = [line.strip() for line in sys.stdin if line.strip()]
def key(name):
    frames = int(re.search(r"frames:(\d+)", name).group(1))
    threads = int(re.search(r"threads:(\d+)", name).group(1))
    return (frames, -threads, name)
print("\n".join(sorted(names, key=key)))')

for name in "${names[@]}"; do
  file="$out/$(echo "$name" | sed 's#/iterations.*##; s#[/:]#_#g').json"
  echo "running $name" >&2
  "$bench" --benchmark_filter="^$(echo "$name" | sed 's/[]\[\.*^$()+?{}|]/\\&/g')\$" \
    --benchmark_out="$file" --benchmark_out_format=json >/dev/null 2>"$file.stderr" ||
    echo "  failed: see $file.stderr" >&2
done
fi

python3 - "$out" <<'PY' | tee "$out/table.md"
import glob, json, math, os, re, sys
rows = []
for path in sorted(glob.glob(os.path.join(sys.argv[1], "*.json"))):
    try:
        benchmarks = json.load(open(path)).get("benchmarks", [])
    except ValueError:  # still being written
        continue
    for b in benchmarks:
        if b.get("run_type") != "iteration":
            continue
        m = re.match(r"TrellisBuild/(\w+)/(\w+)/frames:(\d+)/threads:(\d+)", b["name"])
        if not m:
            continue
        b["data"], b["mode"], b["frames"], b["threads"] = m.group(1), m.group(2), int(m.group(3)), int(m.group(4))
        rows.append(b)

def fmt(value, digits=0):
    return "-" if value is None else f"{value:,.{digits}f}"

def seconds(b):  # benchmark time unit is seconds (Unit(kSecond))
    return b["real_time"] if b.get("time_unit") == "s" else b["real_time"] * {"ms": 1e-3, "us": 1e-6, "ns": 1e-9}[b["time_unit"]]

print("| data | search | frames | threads | build s | frames/s | us/column | evaluations/column | recall (500 cols) | peak RSS B/frame | peak RSS MB | search CPU/wall | exact build s | LSH speedup vs exact | build CPU s | exact search CPU s (extrap.) | LSH CPU speedup vs exact |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for b in sorted(rows, key=lambda b: (b["data"], b["frames"], b["mode"], -b["threads"])):
    if b.get("error_occurred"):
        print(f"| {b['data']} | {b['mode']} | {b['frames']:,} | {b['threads']} | skipped: {b.get('error_message', '')} |")
        continue
    mode = b["mode"] + (" (EXTRAPOLATED)" if b["mode"] == "exact_extrapolated" else "")
    exact_s = b.get("exact_extrapolated_s")
    if b["mode"] == "exact":
        exact_s = seconds(b)
    extrapolated = b["mode"] == "lsh" or b["mode"] == "exact_extrapolated"
    print(f"| {b['data']} | {mode} | {b['frames']:,} | {b['threads']} | {fmt(seconds(b), 1)} | "
          f"{fmt(b.get('items_per_second'))} | {fmt(b.get('us_per_column'), 1)} | "
          f"{fmt(b.get('evaluations_per_column'))} | {fmt(b.get('recall'), 3)} | "
          f"{fmt(b.get('peak_rss_bytes_per_frame'), 1)} | {fmt(b.get('peak_rss_mb'), 0)} | "
          f"{fmt(b.get('search_cpu_per_wall'), 2)} | "
          f"{fmt(exact_s, 1)}{' (extrap.)' if extrapolated and exact_s is not None and b['mode'] != 'exact' else ''} | "
          f"{fmt(b.get('speedup_vs_exact'), 1)} | {fmt(b.get('build_cpu_s'), 1)} | "
          f"{fmt(b.get('exact_search_cpu_extrapolated_s'), 1)} | {fmt(b.get('cpu_speedup_vs_exact'), 1)} |")

# Crossover: full LSH vs full exact builds at the same size and threads.
print()
print("| data | frames | LSH build s | exact build s | exact / LSH (wall) | exact / LSH (CPU) |")
print("| --- | --- | --- | --- | --- | --- |")
for b in sorted(rows, key=lambda b: (b["data"], b["frames"])):
    if b["mode"] != "lsh" or b.get("error_occurred"):
        continue
    for e in rows:
        if e["mode"] == "exact" and not e.get("error_occurred") and (e["data"], e["frames"], e["threads"]) == (b["data"], b["frames"], b["threads"]):
            cpu = f"{e['build_cpu_s'] / b['build_cpu_s']:.2f}" if "build_cpu_s" in e and "build_cpu_s" in b else "-"
            print(f"| {b['data']} | {b['frames']:,} | {seconds(b):.1f} | {seconds(e):.1f} | {seconds(e) / seconds(b):.2f} | {cpu} |")

# Growth exponents between successive LSH sizes (2 threads): time ~ N^k.
print()
for data in sorted({b["data"] for b in rows}):
    pts = sorted((b["frames"], seconds(b)) for b in rows if b["data"] == data and b["mode"] == "lsh" and b["threads"] == 2 and not b.get("error_occurred"))
    if len(pts) >= 2:
        k = [f"{a[0]:,}->{c[0]:,}: {math.log(c[1] / a[1]) / math.log(c[0] / a[0]):.2f}" for a, c in zip(pts, pts[1:])]
        print(f"- {data} LSH build time exponent (time ~ N^k) " + "; ".join(k))
PY
echo
cat "$out/machine.md"
echo "raw JSON: $out"
