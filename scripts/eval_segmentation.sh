#!/usr/bin/env bash
# Temporal segmentation of joined takes (docs/benchmarks.md, "Segmentation of joined takes"):
# `motifmine segment` with its defaults (the EMD between the windows' bags of words) and with the
# paper's motif signatures (`--signature motifs`), against the DTW kNN baseline over the windows'
# frames, on TRIALS takes each joined from pieces of five activities
# (scripts/segmentation_trials.py), the other labelled takes as the training set.
#
# usage: scripts/eval_segmentation.sh [MOCAP_DIR] [OUT_DIR] [TRIALS] [SEED...]
#   MOCAP_DIR  default ../shared/data/mocap
#   OUT_DIR    default out/eval-segmentation
#   TRIALS     default 10
#   SEED...    default 1 2 3: one embedding, motifs and signatures (`motifmine words --seed S`)
#              per seed; the motif signatures' scores are given per seed and as their mean; the
#              word bags and DTW do not depend on the seed and run once
#   SEGMENT_ARGS (environment) extra options for the supervised `motifmine segment` runs
#   WORDS_ARGS (environment) extra options for `motifmine words` (e.g. "--motifs 50")
#   SKIP_DTW=1 (environment) leaves the baseline out
#   LEAVE_ONE_OUT=1 (environment) also segments every labelled source take against the others
#              (word signatures, motif signatures of the first seed, DTW) and prints, per method,
#              the share of each label's frames given it and the takes whose majority label is
#              right (about 2 min, and 3 min more for DTW)
# Score per trial: per-frame balanced accuracy (the mean over the trial's activities of the
# fraction of that activity's frames given its label), ignoring the frames within GUARD (30
# frames, 0.25 s) of each junction; and, unsupervised, the share of junctions with a boundary
# within 1 s. Ends with the line
# `mean balanced accuracy: signatures W, motif signatures S ± SD, dtw D`.
# Needs build/motifmine (scripts/build.sh) and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
MOCAP=${1:-../shared/data/mocap}
OUT=${2:-out/eval-segmentation}
TRIALS=${3:-10}
shift $(( $# > 3 ? 3 : $# ))
SEEDS=${*:-1 2 3}
TOOL=build/motifmine
mkdir -p "$OUT"
python3 scripts/mocap_labels.py "$MOCAP/INDEX.tsv" > "$OUT/labels.tsv"
scripts/import_cmu_takes.sh "$OUT/source.mfs" "$MOCAP"
rm -rf "$OUT/trials" "$OUT/eval.mfs" "$OUT"/eval.mw?
python3 scripts/segmentation_trials.py "$TOOL" "$OUT/source.mfs" "$OUT/labels.tsv" "$OUT/trials" "$TRIALS"
# The archive: every source take, then the joined trials (frames kept as written).
cp "$OUT/source.mfs" "$OUT/eval.mfs"
"$TOOL" import "$OUT/eval.mfs" "$OUT"/trials/trial_*.bvh --first-frame keep --quiet
for seed in $SEEDS; do
  # shellcheck disable=SC2086 # WORDS_ARGS is a list of options
  "$TOOL" words "$OUT/eval.mfs" --seed "$seed" --prefix "$OUT/seed$seed" --quiet \
    ${WORDS_ARGS:-} > /dev/null
done
for trial in "$OUT"/trials/trial_*.bvh; do
  name=$(basename "$trial" .bvh)
  # shellcheck disable=SC2086 # SEGMENT_ARGS is a list of options
  "$TOOL" segment "$OUT/eval.mfs" --prefix "$OUT/seed${SEEDS%% *}" --clip "$name" --quiet \
    --labels "$OUT/trials/$name.labels.tsv" --out "$OUT/words/$name" ${SEGMENT_ARGS:-} > /dev/null
  for seed in $SEEDS; do
    # shellcheck disable=SC2086
    "$TOOL" segment "$OUT/eval.mfs" --prefix "$OUT/seed$seed" --clip "$name" --quiet \
      --labels "$OUT/trials/$name.labels.tsv" --signature motifs --out "$OUT/emd$seed/$name" \
      ${SEGMENT_ARGS:-} > /dev/null
    "$TOOL" segment "$OUT/eval.mfs" --prefix "$OUT/seed$seed" --clip "$name" --quiet \
      --out "$OUT/unsupervised$seed/$name" > /dev/null
  done
  if [ -z "${SKIP_DTW:-}" ]; then
    # shellcheck disable=SC2086
    "$TOOL" segment "$OUT/eval.mfs" --prefix "$OUT/seed${SEEDS%% *}" --clip "$name" --quiet \
      --labels "$OUT/trials/$name.labels.tsv" --distance dtw --out "$OUT/dtw/$name" \
      ${SEGMENT_ARGS:-} > /dev/null
  fi
done
if [ -n "${LEAVE_ONE_OUT:-}" ]; then
  first_seed=${SEEDS%% *}
  methods="words motifs"
  [ -z "${SKIP_DTW:-}" ] && methods="$methods dtw"
  for method in $methods; do
    case $method in
      words) args=() ;;
      motifs) args=(--signature motifs) ;;
      dtw) args=(--distance dtw) ;;
    esac
    "$TOOL" segment "$OUT/eval.mfs" --prefix "$OUT/seed$first_seed" --labels "$OUT/labels.tsv" \
      "${args[@]}" --quiet --out "$OUT/leave-one-out/$method" > /dev/null
  done
  # shellcheck disable=SC2086 # methods is a list
  python3 - "$OUT" $methods <<'PY'
import collections, json, sys
out, methods = sys.argv[1], sys.argv[2:]
labels = {}
for line in open(f"{out}/labels.tsv"):
    fields = line.rstrip("\n").split("\t")
    if fields[0] != "clip" and not fields[0].startswith("#"):
        labels[fields[0]] = fields[1]
for method in methods:
    right, total, by_take = collections.Counter(), collections.Counter(), {}
    for segment in json.load(open(f"{out}/leave-one-out/{method}/segments.json"))["segments"]:
        label = labels.get(segment["clip"])
        if label is None:
            continue
        frames = segment["end"] - segment["start"]
        total[label] += frames
        right[label] += frames * (segment["label"] == label)
        by_take.setdefault(segment["clip"], collections.Counter())[segment["label"]] += frames
    takes, takes_right = collections.Counter(), collections.Counter()
    for clip, votes in by_take.items():
        takes[labels[clip]] += 1
        takes_right[labels[clip]] += votes.most_common(1)[0][0] == labels[clip]
    balanced = sum(right[label] / total[label] for label in total) / len(total)
    print(f"leave one take out, {method}: balanced frame accuracy {balanced:.3f}, takes by majority "
          f"{sum(takes_right.values())}/{sum(takes.values())}; " +
          ", ".join(f"{label} {right[label] / total[label]:.2f} ({takes_right[label]}/{takes[label]})"
                    for label in sorted(total)))
PY
fi
# shellcheck disable=SC2086 # SEEDS is a list
python3 - "$OUT" $SEEDS <<'PY'
import json, os, statistics, sys
out, seeds = sys.argv[1], sys.argv[2:]
GUARD = 30
plan = json.load(open(f"{out}/trials/trials.json"))
fps = plan["fps"]

def frame_labels(segments, frames):
    labels = [None] * frames
    for segment in segments:
        for frame in range(segment["start"], segment["end"]):
            labels[frame] = segment["label"]
    return labels

def balanced(trial, method):
    path = f"{out}/{method}/{trial['trial']}/segments.json"
    if not os.path.exists(path):
        return None
    found = frame_labels(json.load(open(path))["segments"], trial["frames"])
    truth = frame_labels(trial["pieces"], trial["frames"])
    junctions = [piece["start"] for piece in trial["pieces"][1:]]
    right, total = {}, {}
    for frame, label in enumerate(truth):
        if any(abs(frame - junction) < GUARD for junction in junctions):
            continue
        total[label] = total.get(label, 0) + 1
        right[label] = right.get(label, 0) + (found[frame] == label)
    return statistics.mean(right[label] / total[label] for label in total)

def pooled(method):
    """Per activity, the share of its frames over all trials given its label."""
    right, total = {}, {}
    for trial in plan["trials"]:
        path = f"{out}/{method}/{trial['trial']}/segments.json"
        if not os.path.exists(path):
            return None
        found = frame_labels(json.load(open(path))["segments"], trial["frames"])
        junctions = [piece["start"] for piece in trial["pieces"][1:]]
        for frame, label in enumerate(frame_labels(trial["pieces"], trial["frames"])):
            if any(abs(frame - junction) < GUARD for junction in junctions):
                continue
            total[label] = total.get(label, 0) + 1
            right[label] = right.get(label, 0) + (found[frame] == label)
    return ", ".join(f"{label} {right[label] / total[label]:.2f}" for label in sorted(total))

def junctions_found(trial, seed):
    doc = json.load(open(f"{out}/unsupervised{seed}/{trial['trial']}/segments.json"))
    boundaries = [segment["start"] for segment in doc["segments"][1:]]
    junctions = [piece["start"] for piece in trial["pieces"][1:]]
    hits = sum(any(abs(b - j) <= fps for b in boundaries) for j in junctions)
    return hits / len(junctions), len(boundaries)

seed_cells = " | ".join(f"seed {seed}" for seed in seeds)
print(f"| trial | frames | pieces (activity: source take) | word signatures (the default) | "
      f"motif signatures: {seed_cells} | DTW | "
      "unsupervised, seed " + seeds[0] + ": junctions within 1 s / boundaries |")
print("|---|---|---|---|" + "---|" * len(seeds) + "---|---|")
words = []
emd = {seed: [] for seed in seeds}
dtw = []
for trial in plan["trials"]:
    words.append(balanced(trial, "words"))
    cells = []
    for seed in seeds:
        emd[seed].append(balanced(trial, f"emd{seed}"))
        cells.append(f"{emd[seed][-1]:.3f}")
    d = balanced(trial, "dtw")
    if d is not None:
        dtw.append(d)
    share, count = junctions_found(trial, seeds[0])
    pieces = ", ".join(f"{p['label']}: {p['clip']}" for p in trial["pieces"])
    print(f"| {trial['trial']} | {trial['frames']} | {pieces} | {words[-1]:.3f} | "
          f"{' | '.join(cells)} | {'-' if d is None else f'{d:.3f}'} | {share:.2f} / {count} |")
means = [statistics.mean(emd[seed]) for seed in seeds]
print("motif signatures per seed: " +
      ", ".join(f"seed {seed} {mean:.3f}" for seed, mean in zip(seeds, means)))
spread = f" ± {statistics.stdev(means):.3f}" if len(means) > 1 else ""
dtw_text = f"{statistics.mean(dtw):.3f}" if dtw else "not run"
for method in ["words"] + [f"emd{seed}" for seed in seeds] + ["dtw"]:
    activities = pooled(method)
    if activities:
        name = {"words": "word signatures", "dtw": "dtw"}.get(method, f"motif signatures, seed {method[3:]}")
        print(f"per activity, {name}: {activities}")
print(f"mean balanced accuracy: signatures {statistics.mean(words):.3f}, "
      f"motif signatures {statistics.mean(means):.3f}{spread}, dtw {dtw_text}")
PY
