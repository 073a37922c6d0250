#!/usr/bin/env bash
# The scaling suite: every stage against N = 2^14, 2^15, ... frames, with its baselines,
# then the "Scaling" section of docs/benchmarks.md (tables) and its plots (docs/benchmarks/*.svg).
#   scripts/bench.sh quick [JOBS]  N up to 2^16-2^17 (minutes)
#   scripts/bench.sh full [JOBS]   N up to 2^24 (FAISS 2^22; the exact search and the reference
#                                  grower are measured while practical and extrapolated above):
#                                  hours; run it niced in the background
#   scripts/bench.sh report DIR... regenerates the docs section and plots from the JSON in DIR
#                                  (a finished or a partial run; with several runs of one mode,
#                                  each job's rows come from the last run that has it)
# JOBS: a comma-separated subset of the jobs below (default: all), e.g. "trellis,mine" or
# "trellis_real".
# Writes bench-results/scale-<mode>-<date>/ (git-ignored): <job>.json (Google Benchmark's JSON,
# written as each benchmark finishes, so an interrupted run keeps what it measured), <job>.log
# (stderr), load.tsv (the load average every 30 s) and machine.json (cores, CPU, memory, load,
# commit, command); then scripts/bench_report.py rewrites the section of docs/benchmarks.md
# between "<!-- bench.sh MODE begin -->" and "<!-- bench.sh MODE end -->" and the plots
# docs/benchmarks/MODE-*.svg. Each job is one process, so Google Benchmark's ->Complexity() fit
# of each family is in its JSON; every benchmark resets the peak-RSS mark before it measures.
# Environment: MOTIF_BUILD_DIR (default build/, built if a program is missing), MOTIF_BENCH_DIR
# (archives and other generated inputs, default /tmp/motifmine-bench, kept for later runs),
# MOTIF_MOCAP_DIR (the real takes, default ../shared/data/mocap), TMPDIR (the grower's trellis
# files: ~7 GB at 2^24), MOTIF_BENCH_SCALE_MAX (caps every job's largest N: a smoke test).
# Bench-only dependencies, not needed by the engine, its tests or CI (installed here if missing):
#   python3-matplotlib     the plots (log-log axes, legends; SVG with text kept as text)
#   libfaiss-dev, libopenblas0-pthread   the FAISS baseline (bench_faiss_range; built only when
#                          FAISS is found, skipped otherwise)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode="${1:-quick}"
bench_packages=(python3-matplotlib libfaiss-dev libopenblas0-pthread)

if [ "$mode" = report ]; then
  shift
  [ $# -gt 0 ] || { echo "usage: scripts/bench.sh report DIR..." >&2; exit 2; }
  exec /usr/bin/python3 "$root/scripts/bench_report.py" "$root" "$@"
fi
case "$mode" in
  quick|full) ;;
  *) echo "usage: scripts/bench.sh quick|full [JOBS] | report DIR..." >&2; exit 2 ;;
esac

missing=()
for package in "${bench_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
    missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing the bench-only packages: ${missing[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >&2
fi

# job | program | benchmark filter | largest N in quick mode | largest N in full mode
# Cheap jobs first; the real-density trellis and mine before the procedural ones (a full run
# that the machine cannot finish keeps the rows that matter most). A job named <stage>_<data>
# is selected by JOBS naming either.
jobs_table="
bandwidth     | bench_memory_bandwidth    | ^MemoryBandwidth/          | 0      | 0
import        | bench_format_import       | ^ImportScale/              | 131072 | 16777216
decode        | bench_format_frame_file   | ^DecodeScale/              | 131072 | 16777216
distance      | bench_kern_distance       | ^DistanceScale/            | 131072 | 16777216
spill         | bench_format_trellis_file | ^SpillScale/               | 131072 | 16777216
cluster       | bench_engine_cluster      | ^ClusterScale/             | 131072 | 16777216
lsh           | bench_engine_lsh          | ^LshScale/                 | 131072 | 16777216
exact         | bench_engine_exact        | ^ExactScale/               | 65536  | 16777216
grow          | bench_engine_grower       | ^GrowScale/                | 131072 | 16777216
faiss         | bench_faiss_range         | ^FaissScale/               | 32768  | 4194304
trellis_real  | bench_engine_trellis      | ^TrellisBuild/resequenced/ | 65536  | 16777216
mine_real     | bench_engine_mine         | ^MineScale/resequenced/    | 65536  | 16777216
trellis_synth | bench_engine_trellis      | ^TrellisBuild/synth/       | 65536  | 16777216
mine_synth    | bench_engine_mine         | ^MineScale/synth/          | 65536  | 16777216
"
only=",${2:-},"
build="${MOTIF_BUILD_DIR:-$root/build}"
out="$root/bench-results/scale-$mode-$(date +%Y%m%d-%H%M%S)"
mkdir -p "$out"

programs=$(echo "$jobs_table" | awk -F'|' 'NF==5 {gsub(/ /, "", $2); print $2}' | sort -u)
for program in $programs; do
  if [ ! -x "$build/bench/$program" ] && [ "$program" != bench_faiss_range ]; then
    MOTIF_BUILD_DIR="$build" "$root/scripts/build.sh" >/dev/null
    break
  fi
done

load_now() { cut -d' ' -f1-3 /proc/loadavg; }
json_string() { /usr/bin/python3 -c 'import json, sys; print(json.dumps(sys.argv[1]))' "$1"; }
commit="$(git -C "$root" rev-parse --short HEAD)"
dirty=false
[ -n "$(git -C "$root" status --porcelain --untracked-files=no)" ] && dirty=true
cat > "$out/machine.json" <<EOF
{
  "mode": "$mode",
  "command": $(json_string "scripts/bench.sh $*"),
  "nproc": $(nproc),
  "cpu_model": $(json_string "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"),
  "memory_gib": $(free -g | awk '/Mem:/{print $2}'),
  "kernel": $(json_string "$(uname -sr)"),
  "commit": "$commit",
  "dirty": $dirty,
  "started": "$(date -u +%FT%TZ)",
  "load_at_start": "$(load_now)"
}
EOF
cat "$out/machine.json"

(while true; do echo "$(date +%s) $(load_now)" >> "$out/load.tsv"; sleep 30; done) &
sampler=$!
trap 'kill $sampler 2>/dev/null || true' EXIT

echo "$jobs_table" | awk -F'|' 'NF==5' |
while IFS='|' read -r job program filter quick_max full_max; do
  job=$(echo $job); program=$(echo $program); filter=$(echo $filter)
  max=$(echo $quick_max); [ "$mode" = full ] && max=$(echo $full_max)
  if [ -n "${MOTIF_BENCH_SCALE_MAX:-}" ] && [ "$max" -gt "$MOTIF_BENCH_SCALE_MAX" ]; then
    max=$MOTIF_BENCH_SCALE_MAX
  fi
  [ "$only" = ",," ] || [[ "$only" == *",$job,"* ]] || [[ "$only" == *",${job%%_*},"* ]] ||
    continue
  if [ ! -x "$build/bench/$program" ]; then
    echo "$job: $build/bench/$program not built (FAISS missing?): skipped" | tee "$out/$job.log" >&2
    continue
  fi
  echo "$(date +%T) $job: $program up to N = $max (load $(load_now))" >&2
  # The stdout JSON is written benchmark by benchmark (an interrupted job keeps its rows).
  # OMP_WAIT_POLICY=PASSIVE: FAISS's OpenMP threads sleep between parallel regions instead of
  # spinning against OpenBLAS's threads on 2 cores (docs/benchmarks.md, FAISS baseline).
  MOTIF_BENCH_MAX_FRAMES="$max" OMP_WAIT_POLICY=PASSIVE "$build/bench/$program" \
    --benchmark_filter="$filter" --benchmark_format=json --benchmark_counters_tabular=true \
    > "$out/$job.json" 2> "$out/$job.log" || echo "  $job failed: see $out/$job.log" >&2
done

kill $sampler 2>/dev/null || true
/usr/bin/python3 - "$out/machine.json" "$(load_now)" <<'PY'
import json, sys, time
path = sys.argv[1]
machine = json.load(open(path))
machine["finished"] = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
machine["load_at_end"] = sys.argv[2]
json.dump(machine, open(path, "w"), indent=2)
PY
/usr/bin/python3 "$root/scripts/bench_report.py" "$root" "$out"
# The floor of each stage of the mine rows and measured/floor (docs/benchmarks.md, "The floor").
if [ -s "$out/bandwidth.json" ]; then
  echo "== measured against the floor (scripts/stage_floor.py $out)"
  /usr/bin/python3 "$root/scripts/stage_floor.py" "$out" || echo "  stage_floor.py failed" >&2
fi
echo "raw JSON: $out"
