#!/usr/bin/env bash
# One end-to-end `motifmine mine` run on a large synthetic archive with planted motifs, for the
# 10^6 and 10^7 rows of docs/benchmarks.md ("motifmine mine end to end"):
#   scripts/bench_mine_e2e.sh FRAMES [--from TAKES_DIR] [DIR]
# Writes DIR/<frames>[-resequenced].mfs once (`motifmine synth --motifs 20 --seed 1`; with --from,
# re-sequenced from those takes) and keeps it, then times `motifmine mine --threads 2` under
# /usr/bin/time -v. Prints the mine's summary (stage times, peak memory, planted-motif scores)
# and the process's wall time and maximum resident set size. DIR: default /tmp/motifmine-e2e.
# MOTIF_BUILD_DIR: the build to use (default build/).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
frames="${1:?usage: bench_mine_e2e.sh FRAMES [--from TAKES_DIR] [DIR]}"
shift
from=()
tag="$frames"
if [ "${1:-}" = --from ]; then
  # Resolved before the cd below, so a path relative to the caller's folder works.
  from=(--from "$(realpath -e "${2:?--from needs a folder of takes}")")
  tag="$frames-resequenced"
  shift 2
fi
dir="${1:-/tmp/motifmine-e2e}"
tool="${MOTIF_BUILD_DIR:-$root/build}/motifmine"
[ -x "$tool" ] || MOTIF_BUILD_DIR="${MOTIF_BUILD_DIR:-$root/build}" "$root/scripts/build.sh" >/dev/null
mkdir -p "$dir"
cd "$dir"
if [ ! -f "$tag.mfs" ]; then
  "$tool" synth "$tag.mfs" --frames "$frames" --motifs 20 --seed 1 "${from[@]}" --progress quiet
fi
echo "$(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%FT%TZ)," \
     "commit $(git -C "$root" rev-parse --short HEAD)"
rm -rf "$tag-out"
/usr/bin/time -v -o "$tag.time" "$tool" mine "$tag.mfs" --out "$tag-out" --threads 2 \
  --progress quiet
grep -E 'Elapsed|Maximum resident|User time|System time' "$tag.time"
