#!/usr/bin/env bash
# Motif quality on real repetitions: mines each labelled take of tests/data/repetitions alone
# with the default options (plus MOTIF_MINE_ARGS, for experiments) and scores the motifs against
# the annotated occurrences with `motifmine score` (a hit: same clip, IoU >= 0.5).
#
#   scripts/eval_repetitions.sh [MOCAP_DIR]     (default ../shared/data/mocap beside the clone)
#
# Prints, per take, the top-ranked motif against the movement it matches best (precision,
# recall), every movement's best motif, the phase-free means (`motifmine score`: back-to-back
# movements scored at the best common shift), the line
#   mean top-1 precision P recall R
# and the oracle gap: the best motif's F1 minus the top motif's, a mean over takes (what the
# ranking loses).
# Environment: MOTIF_MINE_ARGS extra `mine` options; MOTIF_EVAL_OUT the work folder (default a
# temporary one, removed at the end); MOTIF_EVAL_TAKES a space-separated subset of clips;
# MOTIF_BUILD_DIR the build folder (built when the tool is missing).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mocap="${1:-$root/../shared/data/mocap}"
labels="$root/tests/data/repetitions"
if [ ! -d "$mocap" ]; then
  echo "eval_repetitions: skipped: no motion-capture folder at $mocap" >&2
  exit 0
fi
tool="${MOTIF_BUILD_DIR:-$root/build}/motifmine"
[ -x "$tool" ] || "$root/scripts/build.sh" >&2
if [ -n "${MOTIF_EVAL_OUT:-}" ]; then
  out="$MOTIF_EVAL_OUT"
  mkdir -p "$out"
else
  out="$(mktemp -d)"
  trap 'rm -rf "$out"' EXIT
fi

while IFS=$'\t' read -r clip file; do
  case "$clip" in clip | '#'* | '') continue ;; esac
  if [ -n "${MOTIF_EVAL_TAKES:-}" ] && ! grep -qw -- "$clip" <<<"$MOTIF_EVAL_TAKES"; then continue; fi
  if [ ! -f "$mocap/$file" ]; then
    echo "eval_repetitions: $clip: $mocap/$file is missing" >&2
    exit 1
  fi
  mkdir -p "$out/$clip"
  # shellcheck disable=SC2086  # MOTIF_MINE_ARGS is a list of options
  "$tool" mine "$mocap/$file" --out "$out/$clip" --quiet --no-report ${MOTIF_MINE_ARGS:-} \
    >"$out/$clip/mine.txt"
  "$tool" score "$out/$clip/motifs.json" "$labels/$clip.tsv" --json >"$out/$clip/score.json"
done <"$labels/takes.tsv"

python3 - "$out" "$labels/takes.tsv" "${MOTIF_EVAL_TAKES:-}" <<'PY'
import json, os, sys
out, takes_path, subset = sys.argv[1], sys.argv[2], sys.argv[3].split()
rows = []
for line in open(takes_path):
    clip = line.split("\t")[0].strip()
    if clip in ("clip", "") or clip.startswith("#") or (subset and clip not in subset):
        continue
    score = json.load(open(os.path.join(out, clip, "score.json")))
    motifs = json.load(open(os.path.join(out, clip, "motifs.json")))
    rows.append((clip, score, motifs))
print("%-20s %7s %6s %6s  %-26s %9s %6s %6s" % ("take", "frames", "eps", "motifs", "top motif ~ movement",
                                                "precision", "recall", "inst"))
for clip, score, motifs in rows:
    top = score["top1"]
    print("%-20s %7d %6.3f %6d  %-26s %9.3f %6.3f %6d" % (
        clip, motifs["frames"], motifs["params"]["eps"], score["motifs"], top["movement"] or "-",
        top["precision"], top["recall"], top["instances"]))
print()
print("best motif per annotated movement:")
for clip, score, _ in rows:
    for match in score["per_movement"]:
        motif = "none" if match["motif"] < 0 else "motif %d" % match["motif"]
        print("  %-20s %-26s %3d occurrences  %-9s precision %.3f recall %.3f" % (
            clip, match["movement"], match["occurrences"], motif, match["precision"], match["recall"]))
n = max(len(rows), 1)
print()
# Phase free (motifmine score): a back-to-back movement scored at the best common shift of the
# top motif's instances, where a cycle starts being the annotator's convention.
print("phase-free mean top-1 precision %.3f recall %.3f" % (
    sum(r[1]["top1_phase_free"]["precision"] for r in rows) / n,
    sum(r[1]["top1_phase_free"]["recall"] for r in rows) / n))
print("mean top-1 precision %.3f recall %.3f" % (sum(r[1]["top1"]["precision"] for r in rows) / n,
                                                  sum(r[1]["top1"]["recall"] for r in rows) / n))
# The ranking's loss: the best motif of a take (highest F1 against the movement it matches best)
# against the top-ranked one; 0 when the top motif is the best the miner found.
gaps = [max([m["f1"] for m in r[1]["per_motif"]] + [0.0]) - r[1]["top1"]["f1"] for r in rows]
print("oracle gap %.3f (best motif's F1 minus the top motif's, mean over takes; %d of %d takes "
      "rank another motif better)" % (sum(gaps) / n, sum(g > 1e-9 for g in gaps), len(rows)))
PY
