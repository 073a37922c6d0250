#!/usr/bin/env bash
# How long `motifmine graph` takes to build its graph on N frames (docs/benchmarks.md, "Motion
# graphs"): an archive of re-sequenced real takes (`motifmine synth --from`, the CMU BVH takes
# cut and joined at random), then `graph --unconstrained` and `graph` (constrained) on it, each
# from nothing built: the trellis and the words are built by the first run that needs them and
# timed separately. Prints graph.json's stage seconds, the counts and /usr/bin/time's wall time
# and peak memory of each run.
#
# usage: scripts/bench_graph.sh FRAMES [OUT_DIR] [MOCAP_DIR]
#   OUT_DIR    default /tmp/motifmine-graph-bench (the archive, its trellis and words: large)
#   MOCAP_DIR  default ../shared/data/mocap
set -euo pipefail
cd "$(dirname "$0")/.."
FRAMES=$1
OUT=${2:-/tmp/motifmine-graph-bench}
MOCAP=${3:-../shared/data/mocap}
TOOL=$(pwd)/build/motifmine
mkdir -p "$OUT"
archive="$OUT/real$FRAMES.mfs"
rm -f "$OUT/real$FRAMES".*
"$TOOL" synth "$archive" --frames "$FRAMES" --from "$MOCAP/bvh" --seed 1 --quiet > /dev/null
start=$("$TOOL" info "$archive" --json | python3 -c "import json,sys; print(json.load(sys.stdin)['clips'][0]['name'])")
run() {  # run NAME ARGS...
  local name=$1
  shift
  /usr/bin/time -f "$name: wall %e s, peak %M kB" "$TOOL" graph "$archive" --start "$start" \
    --seconds 60 --out "$OUT/$name$FRAMES" --quiet "$@" > "$OUT/$name$FRAMES.txt" 2> "$OUT/$name$FRAMES.time" ||
    true
  tail -1 "$OUT/$name$FRAMES.time"
  python3 - "$OUT/$name$FRAMES/graph.json" <<'PY'
import json, sys
graph = json.load(open(sys.argv[1]))
print("  seconds", {k: round(v, 2) for k, v in graph["seconds"].items()})
print("  counts ", graph["counts"])
PY
}
echo "frames $FRAMES (start $start)"
run unconstrained --unconstrained
/usr/bin/time -f "words: wall %e s, peak %M kB" "$TOOL" words "$archive" --quiet > /dev/null 2> "$OUT/words$FRAMES.time"
tail -1 "$OUT/words$FRAMES.time"
run constrained
