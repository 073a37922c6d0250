#!/usr/bin/env bash
# The distributed mine against one process, one thread per process, for docs/benchmarks.md
# ("motifmine-mpi: scaling") and the model of docs/design/distributed.md:
#   scripts/bench_mpi_scaling.sh FRAMES [RUNS] [DIR]
# Writes DIR/<frames>.mfs once (`motifmine synth --motifs 20 --seed 1`), then RUNS times (default
# 3), in turn: `motifmine mine --threads 1`, `mpirun -np 1 motifmine-mpi mine --threads 1` and
# `mpirun -np 2 motifmine-mpi mine --threads 1`, each into an empty folder. Prints every run's
# wall time, the medians, the speed-up of 2 ranks over one process, the trellis's stage times
# and the bytes each rank sent. DIR: default /tmp/motifmine-mpi-bench. MOTIF_BUILD_DIR: the build
# (default build/). Needs mpirun (openmpi-bin).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
frames="${1:?usage: bench_mpi_scaling.sh FRAMES [RUNS] [DIR]}"
runs="${2:-3}"
dir="${3:-/tmp/motifmine-mpi-bench}"
build="${MOTIF_BUILD_DIR:-$root/build}"
command -v mpirun >/dev/null || { echo "mpirun not found (openmpi-bin)" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$dir"
cd "$dir"
if [ ! -f "$frames.mfs" ]; then
  "$build/motifmine" synth "$frames.mfs" --frames "$frames" --motifs 20 --seed 1 --progress quiet
fi
echo "$(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%FT%TZ)," \
     "commit $(git -C "$root" rev-parse --short HEAD), $frames frames, $runs runs"

declare -A times
run() {  # run NAME COMMAND...: one timed run into an empty folder
  local name="$1" out="$dir/out-$1"
  shift
  rm -rf "$out"
  local start end
  start=$(date +%s.%N)
  "$@" mine "$frames.mfs" --out "$out" --threads 1 --no-report --quiet > "$dir/$name.log" 2>&1
  end=$(date +%s.%N)
  local seconds
  seconds=$(awk -v a="$start" -v b="$end" 'BEGIN {printf "%.2f", b - a}')
  times[$name]+="$seconds "
  printf '  %-10s %7.2f s\n' "$name" "$seconds"
}
median() { tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

for ((i = 1; i <= runs; i++)); do
  echo "run $i"
  run process "$build/motifmine"
  run ranks1 mpirun -np 1 "$build/motifmine-mpi"
  run ranks2 mpirun -np 2 "$build/motifmine-mpi"
done
echo "medians:"
for name in process ranks1 ranks2; do
  printf '  %-10s %7.2f s   (%s)\n' "$name" "$(echo "${times[$name]}" | median)" "${times[$name]}"
done
echo "speed-up of 2 ranks over one process: $(awk -v a="$(echo "${times[process]}" | median)" \
  -v b="$(echo "${times[ranks2]}" | median)" 'BEGIN {printf "%.2f", a / b}')"
for name in process ranks1 ranks2; do
  echo "$name, last run:"
  grep -E '^  (time|trellis|ranks|searching) ' "$dir/$name.log" | grep -v 'mean K' || true
done
