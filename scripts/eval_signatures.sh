#!/usr/bin/env bash
# Whole-take retrieval and classification of the real CMU takes (docs/benchmarks.md, "Motion
# signatures on the real takes"): signatures with the EMD, against signatures without TF-IDF, DTW
# over the frames and the movement distance, with labels derived from INDEX.tsv
# (scripts/mocap_labels.py).
#
# usage: scripts/eval_signatures.sh [MOCAP_DIR] [OUT_DIR] [SEED...]
#   MOCAP_DIR  default ../shared/data/mocap
#   OUT_DIR    default out/eval-signatures (the archive, the words files and the results)
#   SEED...    default 1 2 3 4 5: one embedding, motifs and signatures per seed
#   WORDS_ARGS (environment) extra options for `motifmine words` (e.g. "--epochs 60")
# The archive holds bvh/ (31-joint MotionBuilder BVH) and the AMC takes that are not also in
# bvh/ (05_01 and the other takes in both formats are imported once). DTW and movement do not
# depend on the seed and run once. Needs build/motifmine (scripts/build.sh) and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
MOCAP=${1:-../shared/data/mocap}
OUT=${2:-out/eval-signatures}
shift $(( $# > 2 ? 2 : $# ))
SEEDS=${*:-1 2 3 4 5}
TOOL=build/motifmine
mkdir -p "$OUT"
python3 scripts/mocap_labels.py "$MOCAP/INDEX.tsv" > "$OUT/labels.tsv"
scripts/import_cmu_takes.sh "$OUT/real.mfs" "$MOCAP"
"$TOOL" info "$OUT/real.mfs" | head -3
if [ ! -f "$OUT/dtw/classify.json" ]; then
  "$TOOL" classify "$OUT/real.mfs" --labels "$OUT/labels.tsv" --distance dtw --quiet --out "$OUT/dtw"
fi
"$TOOL" classify "$OUT/real.mfs" --labels "$OUT/labels.tsv" --distance movement --quiet \
  --out "$OUT/movement" > /dev/null
for seed in $SEEDS; do
  # shellcheck disable=SC2086 # WORDS_ARGS is a list of options
  "$TOOL" words "$OUT/real.mfs" --seed "$seed" --prefix "$OUT/seed$seed" --quiet \
    --json "$OUT/seed$seed.words.json" ${WORDS_ARGS:-} > /dev/null
  for distance in emd emd-tf; do
    "$TOOL" classify "$OUT/real.mfs" --labels "$OUT/labels.tsv" --distance "$distance" \
      --prefix "$OUT/seed$seed" --seed "$seed" --quiet --out "$OUT/seed$seed-$distance" > /dev/null
  done
done
python3 - "$OUT" $SEEDS <<'PY'
import json, statistics, sys
out, seeds = sys.argv[1], sys.argv[2:]
def scores(path):
    doc = json.load(open(path))
    return (doc["supervised"]["accuracy"], doc["retrieval"]["precision"],
            doc["unsupervised"]["adjusted_rand_index"], doc["unsupervised"]["purity"])
def line(name, rows):
    cols = list(zip(*rows))
    cells = []
    for col in cols:
        if len(col) > 1:
            cells.append(f"{statistics.mean(col):.3f} ± {statistics.stdev(col):.3f}")
        else:
            cells.append(f"{col[0]:.3f}")
    print(f"| {name} | " + " | ".join(cells) + " |")
dtw = json.load(open(f"{out}/dtw/classify.json"))
print(f"takes {len(dtw['takes'])}, labelled {dtw['supervised']['labelled']}, seeds {' '.join(seeds)}")
print("| distance | 1-NN leave-one-out accuracy | precision@5 | ARI (MDS + k-means) | purity |")
print("|---|---|---|---|---|")
line("signatures + EMD", [scores(f"{out}/seed{s}-emd/classify.json") for s in seeds])
line("signatures without TF-IDF + EMD", [scores(f"{out}/seed{s}-emd-tf/classify.json") for s in seeds])
line("DTW over the frames", [scores(f"{out}/dtw/classify.json")])
line("movement (what moves and how)", [scores(f"{out}/movement/classify.json")])
print()
print("| seed | EMD 1-NN | EMD p@5 | no TF-IDF 1-NN | no TF-IDF p@5 | held-out triplet accuracy: trained / untrained / raw | training s |")
print("|---|---|---|---|---|---|---|")
for s in seeds:
    e = scores(f"{out}/seed{s}-emd/classify.json")
    t = scores(f"{out}/seed{s}-emd-tf/classify.json")
    w = json.load(open(f"{out}/seed{s}.words.json"))["training"]
    secs = json.load(open(f"{out}/seed{s}.words.json"))["seconds"]
    train = secs["pool"] + secs["neighbours"] + secs["train"]
    print(f"| {s} | {e[0]:.3f} | {e[1]:.3f} | {t[0]:.3f} | {t[1]:.3f} | "
          f"{w['accuracy_trained']:.3f} / {w['accuracy_untrained']:.3f} / {w['accuracy_raw']:.3f} | {train:.0f} |")
PY
