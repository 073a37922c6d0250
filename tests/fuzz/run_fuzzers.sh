#!/usr/bin/env bash
# Runs the libFuzzer targets one after another (docs/reliability.md, "Fuzzing"), each for a
# number of executions, at the lowest CPU priority, with its corpus seeded from fuzz_seed_maker
# (with the CMU takes when ../shared/data/mocap is there) and from tests/data/fuzz/<target>/.
#
#   tests/fuzz/run_fuzzers.sh BUILD_DIR WORK_DIR [RUNS] [TARGET...]
#
# BUILD_DIR: a build configured with -DMOTIF_BUILD_FUZZERS=ON (clang) and built with
# `--target motif_fuzzers`. WORK_DIR (outside the repository) receives <target>/corpus,
# <target>/artifacts (crash, leak, timeout and OOM inputs) and <target>/run.log, whose last
# lines hold the figures. RUNS defaults to 10000000. TARGETs default to all of them.
# A target that finds a crash stops there; the script goes on with the next one and exits 1.
# FUZZ_TIMEOUT: seconds an input may take before it counts as a hang (default 10).
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
if [ $# -lt 2 ]; then
  sed -n '2,14p' "${BASH_SOURCE[0]}" >&2
  exit 2
fi
build_dir="$(cd "$1" && pwd)"
work_dir="$2"
runs="${3:-10000000}"
shift $(( $# < 3 ? $# : 3 ))
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(bvh_parser asf_parser amc_parser frame_file_reader trellis_file_reader
           paths_file_reader)
fi
mocap="${MOTIF_MOCAP_DIR:-$root/../shared/data/mocap}"
# Seconds one input may take (wall time) before libFuzzer reports a timeout. At nice 19 on a
# machine busy with other work a process can be descheduled for seconds: raise it there.
timeout="${FUZZ_TIMEOUT:-10}"

# Longest input per target: a few frames of a real take (BVH), a whole CMU skeleton (ASF),
# archives and trellises of a few blocks.
declare -A max_len=(
  [bvh_parser]=24576 [asf_parser]=16384 [amc_parser]=8192
  [frame_file_reader]=16384 [trellis_file_reader]=8192 [paths_file_reader]=4096
)

mkdir -p "$work_dir"
work_dir="$(cd "$work_dir" && pwd)"
seeds="$work_dir/seeds"
if [ ! -d "$seeds" ]; then
  if [ -d "$mocap" ]; then
    "$build_dir/tests/fuzz/fuzz_seed_maker" "$seeds" --mocap "$mocap"
  else
    "$build_dir/tests/fuzz/fuzz_seed_maker" "$seeds"
  fi
fi
# The scratch files of the reader targets: in memory when possible.
if [ -d /dev/shm ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi

status=0
for target in "${targets[@]}"; do
  dir="$work_dir/$target"
  mkdir -p "$dir/corpus" "$dir/artifacts"
  cp -n "$seeds/$target"/* "$root/tests/data/fuzz/$target"/* "$dir/corpus/" 2>/dev/null || true
  options=(-runs="$runs" -max_len="${max_len[$target]}" -timeout="$timeout" -rss_limit_mb=2048
           -print_final_stats=1 -artifact_prefix="$dir/artifacts/")
  if [ -f "$root/tests/fuzz/$target.dict" ]; then
    options+=(-dict="$root/tests/fuzz/$target.dict")
  fi
  echo "$target: started $(date -u +%FT%TZ), ${runs} runs" | tee "$dir/run.log"
  start=$(date +%s)
  nice -n 19 "$build_dir/tests/fuzz/${target}_fuzz" "${options[@]}" "$dir/corpus" \
    >>"$dir/run.log" 2>&1
  result=$?
  end=$(date +%s)
  echo "$target: exit $result, wall $((end - start)) s, ended $(date -u +%FT%TZ)" |
    tee -a "$dir/run.log"
  grep -E "^#[0-9]+[[:space:]]+DONE|stat::number_of_executed_units|stat::average_exec_per_sec" \
    "$dir/run.log" | tail -3
  if [ $result -ne 0 ]; then status=1; fi
done
exit $status
