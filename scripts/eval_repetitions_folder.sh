#!/usr/bin/env bash
# Motif quality on a folder of mixed real takes: the labelled takes of tests/data/repetitions
# imported into ONE archive (on the first take's CMU body: the Daz take 14_07 is mapped onto
# it, docs/design/mixed_skeletons.md; a take whose skeleton cannot be is named and left out),
# mined together with the default options (plus
# MOTIF_MINE_ARGS), and every motif scored against the takes' joined annotations with
# `motifmine score` (a hit: same clip, IoU >= 0.5; a movement named alike in several takes,
# e.g. gait-cycle, is one movement). Complements scripts/eval_repetitions.sh, which mines each
# take alone.
#
#   scripts/eval_repetitions_folder.sh [MOCAP_DIR]   (default ../shared/data/mocap beside the clone)
#
# Prints `motifmine score`'s report and ends with one line
#   folder all motifs recall R precision P top-1 precision T
# Environment: MOTIF_MINE_ARGS extra `mine` options; MOTIF_EVAL_OUT the work folder (default a
# temporary one, removed at the end; an existing one is emptied first, since `mine` resumes a
# folder it finished); MOTIF_BUILD_DIR the build folder (built when the tool is missing).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mocap="${1:-$root/../shared/data/mocap}"
labels="$root/tests/data/repetitions"
if [ ! -d "$mocap" ]; then
  echo "eval_repetitions_folder: skipped: no motion-capture folder at $mocap" >&2
  exit 0
fi
tool="${MOTIF_BUILD_DIR:-$root/build}/motifmine"
[ -x "$tool" ] || "$root/scripts/build.sh" >&2
if [ -n "${MOTIF_EVAL_OUT:-}" ]; then
  out="$MOTIF_EVAL_OUT"
  rm -rf "$out"
  mkdir -p "$out"
else
  out="$(mktemp -d)"
  trap 'rm -rf "$out"' EXIT
fi

archive="$out/folder.mfs"
truth="$out/truth.tsv"
printf 'clip\tmovement\tstart\tend\n' >"$truth"
while IFS=$'\t' read -r clip file; do
  case "$clip" in clip | '#'* | '') continue ;; esac
  if [ ! -f "$mocap/$file" ]; then
    echo "eval_repetitions_folder: $clip: $mocap/$file is missing" >&2
    exit 1
  fi
  set +e
  "$tool" import "$archive" "$mocap/$file" --quiet >"$out/import.txt" 2>&1
  code=$?
  set -e
  if [ "$code" -eq 13 ] && grep -q "skeleton" "$out/import.txt"; then
    echo "eval_repetitions_folder: $clip left out: $(grep -m1 skeleton "$out/import.txt")" >&2
    continue
  elif [ "$code" -ne 0 ]; then
    cat "$out/import.txt" >&2
    exit "$code"
  fi
  tail -n +2 "$labels/$clip.tsv" >>"$truth"
done <"$labels/takes.tsv"

# shellcheck disable=SC2086  # MOTIF_MINE_ARGS is a list of options
"$tool" mine "$archive" --out "$out/mined" --quiet --no-report ${MOTIF_MINE_ARGS:-} >"$out/mine.txt"
"$tool" score "$out/mined/motifs.json" "$truth"
"$tool" score "$out/mined/motifs.json" "$truth" --json >"$out/score.json"
python3 - "$out/score.json" <<'PY'
import json, sys
score = json.load(open(sys.argv[1]))
print(f"folder all motifs recall {score['recall']:.3f} precision {score['precision']:.3f} "
      f"top-1 precision {score['top1']['precision']:.3f}")
PY
