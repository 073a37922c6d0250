#!/usr/bin/env bash
# Constrained against unconstrained motion graphs (docs/benchmarks.md, "Motion graphs"): random
# walks started in a salsa take over an archive of mixed dances, and the share of each walk that
# stays in salsa.
#
# usage: scripts/eval_graph.sh [MOCAP_DIR] [OUT_DIR] [SEEDS] [SECONDS]
#   MOCAP_DIR  default ../shared/data/mocap
#   OUT_DIR    default out/eval-graph
#   SEEDS      default 10: walks with seeds 1..SEEDS, walk s starting in salsa take 60_0s / 60_10
#              (cycling through 60_01 .. 60_10)
#   SECONDS    default 60
# The archive: salsa (60_*, 61_*), Macarena (143_35), chicken dance (18_15), Russian dance
# (90_30), the animal dances (55_12, 55_25), modern dance (bvh/05_*), boxing (17_10), a kata
# (135_06). One trellis and one set of words (seed 1) serve every walk. A walk's share in salsa
# counts the frames it plays (walk.json's pieces, each junction's blended frames once) whose
# take is a salsa take. Ends with the line
# `salsa share: constrained C (min m), unconstrained U (min u)`.
# Needs build/motifmine (scripts/build.sh) and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
MOCAP=${1:-../shared/data/mocap}
OUT=${2:-out/eval-graph}
SEEDS=${3:-10}
SECONDS_WALK=${4:-60}
TOOL=build/motifmine
mkdir -p "$OUT"
if [ ! -f "$OUT/dances.mfs" ]; then
  "$TOOL" import "$OUT/dances.mfs" "$MOCAP"/asfamc/60/*.amc "$MOCAP"/asfamc/61/*.amc \
    "$MOCAP"/asfamc/143/*.amc "$MOCAP"/asfamc/18/*.amc "$MOCAP"/asfamc/90/*.amc \
    "$MOCAP"/asfamc/55/*.amc "$MOCAP"/asfamc/17/*.amc "$MOCAP"/asfamc/135/*.amc \
    "$MOCAP"/bvh/05_*.bvh --quiet
fi
"$TOOL" info "$OUT/dances.mfs" | head -3
for seed in $(seq 1 "$SEEDS"); do
  take=$(printf '60_%02d' $(( (seed - 1) % 10 + 1 )))
  for mode in constrained unconstrained; do
    flag=()
    [ "$mode" = unconstrained ] && flag=(--unconstrained)
    "$TOOL" graph "$OUT/dances.mfs" --start "$take" --seconds "$SECONDS_WALK" --seed "$seed" \
      --out "$OUT/$mode/$seed" --quiet "${flag[@]}" > "$OUT/$mode.$seed.txt" 2>&1 ||
      { cat "$OUT/$mode.$seed.txt"; exit 1; }
  done
done
python3 - "$OUT" "$SEEDS" <<'PY'
import json, statistics, sys
out, seeds = sys.argv[1], int(sys.argv[2])
def share(walk):
    blend = walk["blend_frames"]
    salsa = total = 0
    for index, piece in enumerate(walk["pieces"]):
        frames = piece["end"] - piece["start"] - (blend if index else 0)
        total += frames
        if piece["clip"].split("_")[0] in ("60", "61"):
            salsa += frames
    return salsa / total
rows, shares = [], {"constrained": [], "unconstrained": []}
for seed in range(1, seeds + 1):
    cells = []
    for mode in ("constrained", "unconstrained"):
        walk = json.load(open(f"{out}/{mode}/{seed}/walk.json"))
        shares[mode].append(share(walk))
        cells += [f"{shares[mode][-1]:.3f}", str(len(walk["pieces"])),
                  ", ".join(sorted({p["clip"] for p in walk["pieces"]}))]
    rows.append(f"| {seed} | {walk['start']} | " + " | ".join(cells) + " |")
for mode in ("constrained", "unconstrained"):
    graph = json.load(open(f"{out}/{mode}/1/graph.json"))
    c = graph["counts"]
    print(f"{mode}: {c['candidates']} window pairs, {c['transitions']} transitions (local minima), "
          f"{c['pruned_signature']} pruned by signature (threshold "
          f"{graph.get('signature_threshold', float('nan')):.4f}), {c['pruned_component']} between "
          f"components, {c['kept']} kept; {c['components']} components, the largest "
          f"{c['largest_component_nodes']} of {c['nodes']} nodes; seconds {graph['seconds']}")
print("| seed | start | constrained: salsa share | pieces | takes | unconstrained: salsa share | pieces | takes |")
print("|---|---|---|---|---|---|---|---|")
print("\n".join(rows))
c, u = shares["constrained"], shares["unconstrained"]
print(f"salsa share: constrained {statistics.mean(c):.3f} (min {min(c):.3f}), "
      f"unconstrained {statistics.mean(u):.3f} (min {min(u):.3f})")
PY
