#!/usr/bin/env bash
# Unsupervised grouping across styles (docs/benchmarks.md, "Segmentation without labels"): the 140
# takes of ../shared/data/bandai2 (10 actions in 7 styles, one action per take) segmented together
# without labels, by each unsupervised signature, and scored by `motifmine score` against the
# action in each take's file name (every frame of a take carries its action). A method that
# groups by action scores high under both rules with about 10 groups; one that groups by style or
# by take scores high only under the majority rule, with many groups.
#
# usage: scripts/eval_segmentation_styles.sh [BANDAI2_DIR] [OUT_DIR]
#   BANDAI2_DIR  default ../shared/data/bandai2 (holding bvh/)
#   OUT_DIR      default out/eval-segmentation-styles
# Prints one line per signature: groups, frame accuracy and macro F1 under both rules.
# Needs build/motifmine (scripts/build.sh) and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${1:-../shared/data/bandai2}
OUT=${2:-out/eval-segmentation-styles}
TOOL=build/motifmine
[[ -d "$DATA/bvh" ]] || { echo "error: $DATA/bvh is missing" >&2; exit 1; }
rm -rf "$OUT"
mkdir -p "$OUT"
"$TOOL" import "$OUT/styles.mfs" "$DATA"/bvh/*.bvh --quiet > /dev/null
"$TOOL" info "$OUT/styles.mfs" --json | python3 -c '
import json, sys
print("clip\tmovement\tstart\tend")
for clip in json.load(sys.stdin)["clips"]:
    name = clip["name"]
    print("\t".join([name, name.split("_")[1], "0", str(clip["frames"])]))
' > "$OUT/labels.tsv"
"$TOOL" words "$OUT/styles.mfs" --seed 1 --quiet > /dev/null
for signature in words motifs; do
  "$TOOL" segment "$OUT/styles.mfs" --signature "$signature" --quiet --out "$OUT/$signature" \
    > /dev/null
  "$TOOL" score "$OUT/$signature/segments.json" "$OUT/labels.tsv" --json > "$OUT/$signature.json"
  python3 - "$signature" "$OUT/$signature.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[2]))
print(f"{sys.argv[1]:7} groups {len(s['groups']):3} for {len(s['labels'])} actions  "
      f"majority {s['majority']['accuracy']:.3f} (F1 {s['majority']['macro_f1']:.3f})  "
      f"hungarian {s['one_to_one']['accuracy']:.3f} (F1 {s['one_to_one']['macro_f1']:.3f})")
PY
done
