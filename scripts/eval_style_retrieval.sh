#!/usr/bin/env bash
# Whole-take retrieval across styles (docs/benchmarks.md, "Whole-take retrieval across styles"):
# the 140 takes of ../shared/data/bandai2 (10 actions, each in 7 styles, 2 takes per action and
# style) classified by `motifmine classify` under each distance. Every take is queried, itself
# excluded, and its nearest takes are scored against the action in their file names (content)
# and, to show what a distance sees first, against the style.
#
# usage: scripts/eval_style_retrieval.sh [BANDAI2_DIR] [OUT_DIR] [SEED]
#   BANDAI2_DIR  default ../shared/data/bandai2 (holding bvh/)
#   OUT_DIR      default out/eval-style-retrieval
#   SEED         default 1: the seed of the words the EMD distances use (movement and dtw have none)
# Prints one table row per distance: content 1-NN accuracy and precision@5, style precision@5;
# then the same for `search --distance movement` run once per take.
# Needs build/motifmine (scripts/build.sh) and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${1:-../shared/data/bandai2}
OUT=${2:-out/eval-style-retrieval}
SEED=${3:-1}
TOOL=build/motifmine
[[ -d "$DATA/bvh" ]] || { echo "error: $DATA/bvh is missing" >&2; exit 1; }
rm -rf "$OUT"
mkdir -p "$OUT"
"$TOOL" import "$OUT/styles.mfs" "$DATA"/bvh/*.bvh --quiet > /dev/null
for field in 1 2; do  # dataset-2_{CONTENT}_{STYLE}_{ID}: 1 the content, 2 the style
  "$TOOL" info "$OUT/styles.mfs" --json | python3 -c '
import json, sys
for clip in json.load(sys.stdin)["clips"]:
    print(clip["name"] + "\t" + clip["name"].split("_")[int(sys.argv[1])])
' "$field" > "$OUT/labels$field.tsv"
done
"$TOOL" words "$OUT/styles.mfs" --seed "$SEED" --quiet > /dev/null
for distance in movement dtw emd; do
  for field in 1 2; do
    "$TOOL" classify "$OUT/styles.mfs" --labels "$OUT/labels$field.tsv" --distance "$distance" \
      --seed "$SEED" --quiet --out "$OUT/$distance-$field" > /dev/null
  done
done
# The same question as a user asks it, one take at a time: `search --clip NAME --distance movement`
# (its distances scaled by the query's own row, take_movement.h), every take queried.
mkdir -p "$OUT/search"
cut -f1 "$OUT/labels1.tsv" | while read -r clip; do
  "$TOOL" search "$OUT/styles.mfs" --clip "$clip" --distance movement --top 5 --quiet \
    --out "$OUT/search/$clip" > /dev/null
done
python3 - "$OUT" <<'PY'
import glob, json, sys
out = sys.argv[1]
print("| distance | content 1-NN | content precision@5 | style precision@5 | seconds |")
print("|---|---|---|---|---|")
for distance in ["movement", "dtw", "emd"]:
    content = json.load(open(f"{out}/{distance}-1/classify.json"))
    style = json.load(open(f"{out}/{distance}-2/classify.json"))
    print(f"| {distance} | {content['supervised']['accuracy']:.3f} | "
          f"{content['retrieval']['precision']:.3f} | {style['retrieval']['precision']:.3f} | "
          f"{content['seconds_distances']:.2f} |")
def field(clip, index):
    return clip.split("_")[index]
hits = {1: [], 2: []}
first = []
seconds = 0
for path in sorted(glob.glob(f"{out}/search/*/search.json")):
    doc = json.load(open(path))
    query = doc["query"]["clip"]
    seconds += doc["seconds"]
    for index in hits:
        found = [field(m["clip"], index) == field(query, index) for m in doc["matches"]]
        hits[index].append(sum(found) / len(found))
    first.append(field(doc["matches"][0]["clip"], 1) == field(query, 1))
print(f"| search --distance movement, {len(hits[1])} queries | "
      f"{sum(first) / len(first):.3f} | {sum(hits[1]) / len(hits[1]):.3f} | "
      f"{sum(hits[2]) / len(hits[2]):.3f} | {seconds:.2f} in all |")
PY
