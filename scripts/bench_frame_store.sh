#!/usr/bin/env bash
# Frame-store measurements for docs/benchmarks.md: compression (against raw float32 and the source
# text), import speed, sequential decode speed, and peak memory while synthesising and reading
# archives of growing size (it must not grow with N).
#   scripts/bench_frame_store.sh [quick|full]   quick: up to 1M frames; full: up to 10M frames
# Archives go to $MOTIF_BENCH_DIR (default /tmp/motifmine-bench) and are removed afterwards.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode="${1:-quick}"
"$root/scripts/build.sh" >/dev/null
build="${MOTIF_BUILD_DIR:-$root/build}"
tool="$build/motifmine"
work="${MOTIF_BENCH_DIR:-/tmp/motifmine-bench}"
mocap="${MOTIF_MOCAP_DIR:-$root/../shared/data/mocap}"
mkdir -p "$work"
trap 'rm -rf "$work"' EXIT

echo "## machine"
echo "- $(nproc) cores, $(free -g | awk '/Mem:/{print $2}') GiB, $(uname -sr), commit $(git -C "$root" rev-parse --short HEAD)"
echo

if [ -d "$mocap/bvh" ]; then
  echo "## real takes: compression and import"
  echo "| input | source bytes | frames | archive bytes | vs source text | vs raw float32 | import wall s (2 threads) |"
  echo "| --- | --- | --- | --- | --- | --- | --- |"
  for set in bvh asfamc; do
    archive="$work/$set.mfs"
    rm -f "$archive"
    line=$(python3 "$root/scripts/peak_rss.py" "$tool" import "$archive" "$mocap/$set" --quiet)
    wall=$(echo "$line" | sed 's/.*wall_s=\([0-9.]*\).*/\1/')
    source_bytes=$(find "$mocap/$set" -type f \( -name '*.bvh' -o -name '*.amc' -o -name '*.asf' \) -printf '%s\n' | awk '{s+=$1} END {print s}')
    "$tool" info "$archive" --json > "$work/info.json"
    python3 - "$work/info.json" "$source_bytes" "$wall" "$set" <<'PY'
import json, sys
info = json.load(open(sys.argv[1])); source = int(sys.argv[2]); wall = float(sys.argv[3])
print(f"| {sys.argv[4]} | {source:,} | {info['frames']:,} | {info['file_bytes']:,} | "
      f"{source / info['file_bytes']:.1f}x | {info['raw_float32_bytes'] / info['file_bytes']:.1f}x | "
      f"{wall:.2f} ({info['frames'] / wall:,.0f} frames/s) |")
PY
  done
  echo
fi

echo "## synthetic archives: synthesis and full read (verify decodes every block), peak memory"
echo "| frames | synth wall s | synth peak RSS MB | archive bytes/frame | verify wall s | read frames/s | verify peak RSS MB |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
sizes="100000 1000000"
[ "$mode" = full ] && sizes="100000 1000000 10000000"
for frames in $sizes; do
  archive="$work/synth-$frames.mfs"
  synth=$(python3 "$root/scripts/peak_rss.py" "$tool" synth "$archive" --frames "$frames" --motifs 10 --seed 1 --force --quiet)
  verify=$(python3 "$root/scripts/peak_rss.py" "$tool" verify "$archive" --quiet)
  bytes=$(stat -c %s "$archive")
  python3 - "$frames" "$synth" "$verify" "$bytes" <<'PY'
import sys
frames = int(sys.argv[1]); bytes_ = int(sys.argv[4])
def parse(line): return dict(kv.split("=") for kv in line.split())
s = parse(sys.argv[2]); v = parse(sys.argv[3])
print(f"| {frames:,} | {float(s['wall_s']):.1f} | {float(s['peak_rss_mb']):.0f} | {bytes_ / frames:.1f} | "
      f"{float(v['wall_s']):.2f} | {frames / float(v['wall_s']):,.0f} | {float(v['peak_rss_mb']):.0f} |")
PY
  rm -f "$archive" "$work/synth-$frames.truth.json"
done
echo
echo "## Google Benchmark: frame file and import"
echo '```'
"$build/bench/bench_format_frame_file" --benchmark_min_time=0.2 --benchmark_repetitions=3 \
  --benchmark_report_aggregates_only=true 2>/dev/null | grep -E 'median|BigO|RMS' || true
if [ -d "$mocap/bvh" ]; then
  "$build/bench/bench_format_import" --benchmark_repetitions=3 \
    --benchmark_report_aggregates_only=true 2>/dev/null | grep -E 'median' || true
fi
echo '```'
