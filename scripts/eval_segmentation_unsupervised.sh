#!/usr/bin/env bash
# Unsupervised temporal segmentation of the exercise routines of ../shared/data/mocap6 (docs/
# benchmarks.md, "Segmentation without labels"): `motifmine segment` without labels and without
# --groups, each take alone and the three together, scored against the per-frame action labels
# by `motifmine score` under the majority and the one-to-one (Hungarian) rule.
#
# usage: scripts/eval_segmentation_unsupervised.sh [MOCAP6_DIR] [OUT_DIR] [SEED...]
#   MOCAP6_DIR  default ../shared/data/mocap6
#   OUT_DIR     default out/eval-segmentation-unsupervised
#   SEED...     default 1 2 3 4 5: the words are built once per seed (`motifmine words --seed S`)
#               and every take is segmented with each
#   SEGMENT_ARGS (environment) extra options for `motifmine segment`
# Prints one line per take (its actions, the groups found, the frame accuracy under both rules:
# mean over the seeds and its range), one for the three together, and ends with the line
# `mean frame accuracy A hungarian H` (the takes alone, mean over takes and seeds).
# Needs build/motifmine (scripts/build.sh) and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${1:-../shared/data/mocap6}
OUT=${2:-out/eval-segmentation-unsupervised}
shift $(( $# > 2 ? 2 : $# ))
SEEDS=${*:-1 2 3 4 5}
TOOL=build/motifmine
TAKES="13_29 13_30 13_31"
for take in $TAKES; do
  [[ -f "$DATA/$take.amc" ]] || { echo "error: $DATA/$take.amc is missing" >&2; exit 1; }
done
rm -rf "$OUT"
mkdir -p "$OUT"
python3 scripts/mocap6_labels.py "$DATA" > "$OUT/labels.tsv"
# shellcheck disable=SC2046 # one path per take
"$TOOL" import "$OUT/mocap6.mfs" $(for take in $TAKES; do echo "$DATA/$take.amc"; done) \
  --asf "$DATA/13.asf" --quiet > /dev/null
clips=()
for take in $TAKES; do clips+=(--clip "$take"); done
for seed in $SEEDS; do
  "$TOOL" words "$OUT/mocap6.mfs" --seed "$seed" --prefix "$OUT/seed$seed" --quiet > /dev/null
  for run in $TAKES together; do
    if [[ $run == together ]]; then which=("${clips[@]}"); else which=(--clip "$run"); fi
    # shellcheck disable=SC2086 # SEGMENT_ARGS is a list of options
    "$TOOL" segment "$OUT/mocap6.mfs" --prefix "$OUT/seed$seed" "${which[@]}" --quiet \
      --out "$OUT/seed$seed/$run" ${SEGMENT_ARGS:-} > /dev/null
    "$TOOL" score "$OUT/seed$seed/$run/segments.json" "$OUT/labels.tsv" --json \
      > "$OUT/seed$seed/$run/score.json"
  done
done
python3 - "$OUT" "$TAKES" "$SEEDS" <<'PY'
import json, os, statistics, sys
out, takes, seeds = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()
def load(seed, run):
    with open(os.path.join(out, "seed" + seed, run, "score.json")) as f:
        return json.load(f)
def actions(score):
    return len(score["labels"])
def line(name, scores):
    major = [s["majority"]["accuracy"] for s in scores]
    hung = [s["one_to_one"]["accuracy"] for s in scores]
    groups = [len(s["groups"]) for s in scores]
    print(f"{name:9} actions {actions(scores[0]):2}  groups {min(groups)}-{max(groups)}  "
          f"majority {statistics.mean(major):.3f} ({min(major):.3f}-{max(major):.3f})  "
          f"hungarian {statistics.mean(hung):.3f} ({min(hung):.3f}-{max(hung):.3f})  "
          f"macro F1 {statistics.mean(s['majority']['macro_f1'] for s in scores):.3f} / "
          f"{statistics.mean(s['one_to_one']['macro_f1'] for s in scores):.3f}")
    return statistics.mean(major), statistics.mean(hung)
print(f"seeds {' '.join(seeds)}; frame accuracy mean over the seeds (min-max)")
alone = [line(take, [load(seed, take) for seed in seeds]) for take in takes]
line("together", [load(seed, "together") for seed in seeds])
print(f"mean frame accuracy {statistics.mean(a for a, _ in alone):.3f} "
      f"hungarian {statistics.mean(h for _, h in alone):.3f}")
PY
